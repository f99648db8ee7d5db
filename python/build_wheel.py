#!/usr/bin/env python3
"""Packs the built package directory (build/python/rlrun: the .py files and the _core
extension) into a wheel, so that a virtualenv gets rlrun with one command and no network:

    VENV/bin/pip install --no-index build/python/dist/rlrun-<version>-cp311-cp311-linux_x86_64.whl

The wheel format is PEP 427 (a zip with <name>-<version>.dist-info/{METADATA, WHEEL, RECORD};
RECORD lists every file with its urlsafe-base64 sha256 and size). The wheel is for this
interpreter's ABI (CPython 3.11 on Debian 12) and any Debian 12 machine with an x86-64-v2 CPU:
the shared libraries the extension links beyond Debian's base system (Bullet, Box2D, MuJoCo,
Cairo and the X11 pieces it pulls in, yaml-cpp, libzip, SUMO's TraCI client, ...; `ldd` says
which) travel in rlrun/.libs, where the extension's DT_RPATH ($ORIGIN/.libs, set at link time:
python/CMakeLists.txt) finds them and their own dependencies. It carries rlrun's shipped data
(configs, scenarios, SUMO networks) in rlrun/share/rlrun (docs/python.md). TrafficNetwork-v0's
SUMO worker runs SUMO itself, which the target machine provides (apt install sumo).

    build_wheel.py --package build/python/rlrun --version 0.1.0 --out build/python/dist
"""

import argparse
import base64
import hashlib
import os
import subprocess
import sys
import sysconfig
import zipfile


def wheel_tag() -> str:
    impl = f"cp{sys.version_info.major}{sys.version_info.minor}"
    platform = sysconfig.get_platform().replace("-", "_").replace(".", "_")
    return f"{impl}-{impl}-{platform}"


# Libraries every Debian 12 system has (glibc, and the Priority: required packages libgcc-s1,
# libstdc++6 (apt needs it) and zlib1g): not bundled. Any other library the extension links is.
BASE_SYSTEM = ("linux-vdso.so", "ld-linux-x86-64.so", "libc.so", "libm.so", "libdl.so",
               "libpthread.so", "librt.so", "libresolv.so", "libgcc_s.so", "libstdc++.so",
               "libz.so")


def in_base_system(soname: str) -> bool:
    return any(soname == s or soname.startswith(s + ".") for s in BASE_SYSTEM)


def bundled_libraries(extension: str):
    """(soname, path) of every library `extension` loads, directly or not, outside the base
    system, as the dynamic loader resolves them here (ldd)."""
    out = subprocess.run(["ldd", extension], check=True, stdout=subprocess.PIPE, text=True).stdout
    libraries = []
    for line in out.splitlines():
        parts = line.split()
        if len(parts) >= 3 and parts[1] == "=>":
            soname, path = parts[0], parts[2]
            if path == "not":
                raise SystemExit(f"build_wheel: {extension} needs {soname}, which is not found")
            if not in_base_system(soname):
                libraries.append((soname, os.path.realpath(path)))
    return libraries


def record_line(name: str, data: bytes) -> str:
    digest = base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode()
    return f"{name},sha256={digest},{len(data)}"


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--package", required=True, help="the built package directory (…/rlrun)")
    parser.add_argument("--version", required=True)
    parser.add_argument("--out", required=True, help="directory for the .whl")
    args = parser.parse_args()

    files = []
    # share/: the shipped data (links to the checkout's configs/, scenarios/, sumo_data/), copied
    # into the wheel so that an installed rlrun finds it beside its extension module.
    for root, dirs, names in os.walk(args.package, followlinks=True):
        dirs[:] = sorted(d for d in dirs if d != "__pycache__")
        data = os.path.relpath(root, args.package).split(os.sep)[0] == "share"
        for name in sorted(names):
            # rlrun-sumo-worker: TrafficNetwork-v0's SUMO worker program, found beside the
            # extension module (as librlrun_libsumo.so, which it loads).
            if data or name.endswith((".py", ".so")) or name == "rlrun-sumo-worker":
                path = os.path.join(root, name)
                files.append((os.path.join("rlrun", os.path.relpath(path, args.package)), path))
    extensions = [path for arc, path in files
                  if arc.startswith("rlrun/_core.") and arc.endswith(".so")]
    if not extensions:
        print(f"build_wheel: no extension module in {args.package}: build the rlrun_python target first",
              file=sys.stderr)
        return 1
    for soname, path in bundled_libraries(extensions[0]):
        files.append((f"rlrun/.libs/{soname}", path))

    tag = wheel_tag()
    dist_info = f"rlrun-{args.version}.dist-info"
    metadata = "\n".join([
        "Metadata-Version: 2.1",
        "Name: rlrun",
        f"Version: {args.version}",
        "Summary: rlrun's trained models, fast envs and training from Python",
        f"Requires-Python: =={sys.version_info.major}.{sys.version_info.minor}.*",
        "Requires-Dist: numpy",
        "",
        "See docs/python.md in the rlrun repository.",
        "",
    ])
    wheel = "\n".join([
        "Wheel-Version: 1.0",
        "Generator: rlrun python/build_wheel.py",
        "Root-Is-Purelib: false",
        f"Tag: {tag}",
        "",
    ])

    os.makedirs(args.out, exist_ok=True)
    target = os.path.join(args.out, f"rlrun-{args.version}-{tag}.whl")
    temp = target + ".tmp"
    records = []
    with zipfile.ZipFile(temp, "w", compression=zipfile.ZIP_DEFLATED) as whl:
        def add(name: str, data: bytes, mode: int = 0o644):
            info = zipfile.ZipInfo(name, date_time=(2020, 1, 1, 0, 0, 0))
            info.external_attr = (0o100000 | mode) << 16
            info.compress_type = zipfile.ZIP_DEFLATED
            whl.writestr(info, data)
            records.append(record_line(name, data))

        for arcname, path in files:
            with open(path, "rb") as f:
                executable = ".so" in os.path.basename(path) or path.endswith("rlrun-sumo-worker")
                add(arcname, f.read(), 0o755 if executable else 0o644)
        add(f"{dist_info}/METADATA", metadata.encode())
        add(f"{dist_info}/WHEEL", wheel.encode())
        add(f"{dist_info}/top_level.txt", b"rlrun\n")
        record = "\n".join(records + [f"{dist_info}/RECORD,,"]) + "\n"
        info = zipfile.ZipInfo(f"{dist_info}/RECORD", date_time=(2020, 1, 1, 0, 0, 0))
        info.external_attr = (0o100644) << 16
        whl.writestr(info, record, compress_type=zipfile.ZIP_DEFLATED)
    os.replace(temp, target)
    bundled = sum(1 for arc, _ in files if arc.startswith("rlrun/.libs/"))
    print(f"build_wheel: {target} ({os.path.getsize(target) / 1e6:.1f} MB, {bundled} shared "
          "libraries bundled in rlrun/.libs)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
