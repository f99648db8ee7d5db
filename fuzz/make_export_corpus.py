"""Seeds of fuzz_export (fuzz/fuzz_export.cpp) from model files rlrun wrote:
    python3 fuzz/make_export_corpus.py OUT_DIR MODEL.zip...
Each model becomes `<OUT_DIR>/<name>`: its members as `@@ <name>\\n<data>`, joined by `\\n`
(fuzz_export splits at `\\n@@ `). The first model also becomes `hostile_meta`: its meta.json's
env_id and rlrun_version hold what tries to end the C header's comment (`*/`, `*\\` newline
`/`, `??/`) and control characters. A member whose data holds the separator is left out."""
import json
import pathlib
import sys
import zipfile

SEPARATOR = b"\n@@ "


def seed(members):
    parts = []
    for name, data in members:
        if SEPARATOR in data or b"\n" in name.encode():
            continue
        parts.append(b"@@ " + name.encode() + b"\n" + data)
    return b"\n".join(parts)


def main():
    out = pathlib.Path(sys.argv[1])
    out.mkdir(parents=True, exist_ok=True)
    for index, path in enumerate(sys.argv[2:]):
        with zipfile.ZipFile(path) as z:
            members = [(name, z.read(name)) for name in z.namelist()
                       if not name.startswith("training/")]
        name = pathlib.Path(path).parent.parent.name  # <run name>/seed1/model.zip
        (out / name).write_bytes(seed(members))
        if index == 0:
            hostile = []
            for member, data in members:
                if member == "meta.json":
                    meta = json.loads(data)
                    meta["env_id"] += " *\\\n/ int injected; /* */ ??/\n \u0000\u001b[2J\u00e9"
                    meta["rlrun_version"] += " *??/\n/ int injected_too;"
                    data = json.dumps(meta, indent=2).encode()
                hostile.append((member, data))
            (out / "hostile_meta").write_bytes(seed(hostile))


main()
