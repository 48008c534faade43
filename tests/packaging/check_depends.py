#!/usr/bin/env python3
"""The Depends each nearshore .deb declares, checked (tests/packaging/run_packages.sh).

Usage: check_depends.py DEB...

- every package with ELF files depends on libc6 and libstdc++6: dpkg-shlibdeps ran;
- libnearshore-dev depends on libnearshore0 of its own version, and not on Eigen or nlohmann_json
  (a C host needs neither: they are only recommended, for the C++ API);
- no run-time package (libnearshore0, nearshore-tools, python3-nearshore, libnearshore-osg0) depends
  on a -dev package;
- libnearshore-osg0 depends on libnearshore0 of its own version and on OpenSceneGraph's library;
  libnearshore-osg-dev on libnearshore-osg0 and libnearshore-dev of its version and on
  libopenscenegraph-dev;
- python3-nearshore depends on the interpreter its extension was built for (a >= and << pair) and
  on python3-numpy;
- every clause is satisfied by this machine's installed packages (dpkg's status file) or by the
  packages given: what a Debian 12 with the build's dependencies needs to install them.
"""
import re
import subprocess
import sys

CLAUSE = re.compile(r"^\s*([a-z0-9][a-z0-9+.-]*)(?::[a-z0-9]+)?\s*(?:\(\s*(<<|<=|=|>=|>>)\s*([^)\s]+)\s*\))?\s*$")


def field(deb, name):
    return subprocess.run(["dpkg-deb", "-f", deb, name], check=True, capture_output=True, text=True).stdout.strip()


def clauses(depends):
    """[[(name, op, version), ...alternatives], ...]"""
    result = []
    for clause in filter(None, (c.strip() for c in depends.split(","))):
        alternatives = []
        for alternative in clause.split("|"):
            match = CLAUSE.match(alternative)
            if not match:
                raise SystemExit(f"unparsable dependency '{alternative}' in '{depends}'")
            alternatives.append(match.groups())
        result.append(alternatives)
    return result


def installed_packages():
    """name -> [versions] of installed packages, with what they provide (versioned or not)."""
    packages = {}
    with open("/var/lib/dpkg/status", encoding="utf-8") as status:
        for stanza in status.read().split("\n\n"):
            fields = dict(re.findall(r"^([A-Za-z-]+): (.*)$", stanza, re.M))
            if not fields.get("Status", "").endswith(" installed"):
                continue
            packages.setdefault(fields["Package"], []).append(fields["Version"])
            for provided in clauses(fields.get("Provides", "")):
                name, op, version = provided[0]
                packages.setdefault(name, []).append(version if op == "=" else None)
    return packages


def satisfied(name, op, version, available):
    for have in available.get(name, []):
        if op is None:
            return True
        if have is not None and subprocess.run(
                ["dpkg", "--compare-versions", have, {"<<": "lt", "<=": "le", "=": "eq", ">=": "ge", ">>": "gt"}[op],
                 version]).returncode == 0:
            return True
    return False


def main(debs):
    packages = {field(deb, "Package"): deb for deb in debs}
    versions = {name: field(deb, "Version") for name, deb in packages.items()}
    available = installed_packages()
    for name, version in versions.items():
        available.setdefault(name, []).append(version)
    problems = []
    for name, deb in packages.items():
        depends = clauses(field(deb, "Depends"))
        names = {alternative[0] for clause in depends for alternative in clause}
        has_elf = name not in ("libnearshore-dev", "libnearshore-osg-dev")
        if has_elf and not {"libc6", "libstdc++6"} <= names:
            problems.append(f"{name}: no libc6 / libstdc++6 in Depends: dpkg-shlibdeps did not run")
        if name in ("libnearshore0", "nearshore-tools", "python3-nearshore", "libnearshore-osg0"):
            problems += [f"{name}: a run-time package depends on {n}" for n in names if n.endswith("-dev")]
        if name == "libnearshore-dev":
            if [("libnearshore0", "=", versions.get("libnearshore0"))] not in depends:
                problems.append(f"{name}: does not depend on libnearshore0 (= {versions.get('libnearshore0')})")
            problems += [f"{name}: a C host would need {n}" for n in names
                         if n in ("libeigen3-dev", "nlohmann-json3-dev") or n.endswith("-dev")]
        if name == "libnearshore-osg0":
            if [("libnearshore0", "=", versions.get("libnearshore0"))] not in depends:
                problems.append(f"{name}: does not depend on libnearshore0 (= {versions.get('libnearshore0')})")
            if not any(n.startswith("libopenscenegraph") for n in names):
                problems.append(f"{name}: no OpenSceneGraph library in Depends: dpkg-shlibdeps did not see it")
        if name == "libnearshore-osg-dev":
            for needed in ("libnearshore-osg0", "libnearshore-dev"):
                if [(needed, "=", versions.get(needed))] not in depends:
                    problems.append(f"{name}: does not depend on {needed} (= {versions.get(needed)})")
            if "libopenscenegraph-dev" not in names:
                problems.append(f"{name}: does not depend on libopenscenegraph-dev (its header includes OSG's)")
        if name == "python3-nearshore":
            ops = {alternative[1] for clause in depends for alternative in clause if alternative[0] == "python3"}
            if not {">=", "<<"} <= ops or "python3-numpy" not in names:
                problems.append(f"{name}: Depends lacks the python3 version range or python3-numpy")
        for clause in depends:
            if not any(satisfied(*alternative, available) for alternative in clause):
                problems.append(f"{name}: '{' | '.join(a[0] + (f' ({a[1]} {a[2]})' if a[1] else '') for a in clause)}'"
                                " is not satisfied on this machine")
        print(f"packages: {name} {versions[name]}: {len(depends)} Depends clauses checked")
    if problems:
        print("\n".join(problems))
        return 1
    print("packages: every Depends clause is as expected and satisfied on this machine")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
