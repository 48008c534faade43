#pragma once
// The OpenEXR encoding of one frame, shared by the writer and the reader (internal).
#include <array>
#include <filesystem>
#include <string>

#include "nearshore/core/raster.hpp"
#include "nearshore/sequence/sequence_reader.hpp"

namespace nearshore::sequence::detail {

/// The complete .exr file of frame `index` as bytes. `channels` are eta, P, Q, breaking in that
/// order, all of the grid's size; a null breaking channel is stored as zeros.
std::string encode_frame(const GridGeometry& geometry, const FrameEncoding& encoding, int index, double time_s,
                         const std::array<const Raster<float>*, 4>& channels);

/// Reads raster rows [first_row, first_row + row_count) of the frame file at `path` (no checksum).
void decode_frame_rows(const std::filesystem::path& path, const SequenceManifest& manifest, int expected_index,
                       int first_row, int row_count, ChannelSelection selection, Frame& frame);

}  // namespace nearshore::sequence::detail
