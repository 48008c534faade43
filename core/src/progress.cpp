#include "nearshore/core/progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>

#include <fmt/core.h>

namespace nearshore {
namespace {
std::atomic<bool> g_quiet{false};
}

void ProgressBar::set_quiet(bool quiet) { g_quiet = quiet; }

std::string format_duration(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return "?";
  if (seconds < 60) return fmt::format("{:.1f} s", seconds);
  auto whole = static_cast<long>(std::lround(seconds));
  if (whole < 3600) return fmt::format("{} min {:02} s", whole / 60, whole % 60);
  return fmt::format("{} h {:02} min", whole / 3600, (whole % 3600) / 60);
}

double remaining_seconds(double elapsed_s, double fraction_done, double fraction_at_start) {
  const double done_here = fraction_done - fraction_at_start;
  if (!(done_here > 1e-9) || !std::isfinite(elapsed_s)) return NAN;
  return elapsed_s * (1.0 - fraction_done) / done_here;
}

ProgressBar::ProgressBar(std::string label, double total, std::string unit, double done_at_start)
    : label_(std::move(label)), unit_(std::move(unit)), total_(std::max(total, 1e-300)),
      fraction_at_start_(std::isfinite(done_at_start) ? std::clamp(done_at_start / total_, 0.0, 1.0) : 0.0),
      start_(std::chrono::steady_clock::now()), last_draw_(start_), terminal_(::isatty(STDERR_FILENO) == 1) {}

ProgressBar::~ProgressBar() {
  if (!finished_) finish();
}

double ProgressBar::elapsed_seconds() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

void ProgressBar::update(double done, std::string_view detail) {
  if (g_quiet || finished_) return;
  const auto now = std::chrono::steady_clock::now();
  if (terminal_) {
    if (now - last_draw_ < std::chrono::milliseconds(100)) return;
    last_draw_ = now;
    draw(done, detail, false);
  } else {
    int decile = static_cast<int>(std::floor(10.0 * std::clamp(done / total_, 0.0, 1.0)));
    if (decile <= last_decile_ || decile >= 10) return;
    last_decile_ = decile;
    draw(done, detail, false);
  }
}

void ProgressBar::finish(std::string_view detail) {
  if (finished_) return;
  finished_ = true;
  if (g_quiet) return;
  draw(total_, detail, true);
}

void ProgressBar::draw(double done, std::string_view detail, bool final_line) {
  const double fraction = std::clamp(done / total_, 0.0, 1.0);
  const double elapsed = elapsed_seconds();
  const double eta = remaining_seconds(elapsed, fraction, fraction_at_start_);
  constexpr int kWidth = 28;
  const int filled = static_cast<int>(std::round(fraction * kWidth));
  std::string bar(filled, '#');
  bar.append(kWidth - filled, '.');
  std::string line =
      final_line ? fmt::format("{:<12} [{}] done in {}{}", label_, bar, format_duration(elapsed),
                               fraction_at_start_ > 0.0 ? fmt::format(" (resumed at {:.1f}%)", 100.0 * fraction_at_start_) : "")
                 : fmt::format("{:<12} [{}] {:5.1f}% {:.4g}/{:.4g} {}  elapsed {}  ETA {}", label_, bar,
                               100.0 * fraction, done, total_, unit_, format_duration(elapsed),
                               format_duration(eta));
  if (!detail.empty()) line += fmt::format("  {}", detail);
  if (terminal_)
    std::fprintf(stderr, "\r\033[K%s%s", line.c_str(), final_line ? "\n" : "");
  else
    std::fprintf(stderr, "%s\n", line.c_str());
  std::fflush(stderr);
}

}  // namespace nearshore
