#!/usr/bin/python3
"""Reads rlrun's TensorBoard event files independently of rlrun, as TensorBoard would, and
checks them against the run's progress.csv.

The TFRecord framing and its masked CRC-32C are checked with a CRC written here (not rlrun's);
the Event / Summary / HParams messages are declared here (field numbers from TensorBoard's
event.proto, summary.proto, tensor.proto and plugins/hparams/plugin_data.proto) and decoded with
Debian's python3-protobuf.

    tfevents.py check TB_RUN_DIR PROGRESS_CSV [--finished]
        every progress.csv key except those SB3 keeps out of TensorBoard appears as a scalar with
        the same steps (time/total_timesteps) and values (float32), no step twice; the HParams
        session start holds the config; --finished: the session end and final/ scalars exist.
        Prints one JSON line with what it found; exit 1 with the reason otherwise.
    tfevents.py dump TB_RUN_DIR     prints the decoded events as JSON lines
"""
import csv
import glob
import json
import math
import os
import struct
import sys

from google.protobuf import descriptor_pb2, descriptor_pool, message_factory, struct_pb2

SB3_EXCLUDED = {"time/iterations", "time/time_elapsed", "time/total_timesteps", "time/episodes",
                "train/n_updates"}

# --- CRC-32C (Castagnoli), bit by bit: slow and obviously right ------------------------------


def crc32c(data):
    crc = 0xFFFFFFFF
    for byte in data:
        crc ^= byte
        for _ in range(8):
            crc = (crc >> 1) ^ 0x82F63B78 if crc & 1 else crc >> 1
    return crc ^ 0xFFFFFFFF


def masked(crc):
    return (((crc >> 15) | (crc << 17)) + 0xA282EAD8) & 0xFFFFFFFF


def records(path):
    """The data of each TFRecord in a file; raises ValueError on a bad length, CRC or tail."""
    with open(path, "rb") as f:
        blob = f.read()
    pos = 0
    while pos < len(blob):
        if pos + 12 > len(blob):
            raise ValueError(f"{path}: {len(blob) - pos} stray bytes at offset {pos}")
        header = blob[pos:pos + 8]
        (length,) = struct.unpack("<Q", header)
        (length_crc,) = struct.unpack("<I", blob[pos + 8:pos + 12])
        if masked(crc32c(header)) != length_crc:
            raise ValueError(f"{path}: bad length CRC at offset {pos}")
        data = blob[pos + 12:pos + 12 + length]
        if len(data) != length or pos + 16 + length > len(blob):
            raise ValueError(f"{path}: record at offset {pos} is cut short")
        (data_crc,) = struct.unpack("<I", blob[pos + 12 + length:pos + 16 + length])
        if masked(crc32c(data)) != data_crc:
            raise ValueError(f"{path}: bad data CRC at offset {pos}")
        yield data
        pos += 16 + length


# --- the messages, declared here ----------------------------------------------------------------

F = descriptor_pb2.FieldDescriptorProto


def message(name, fields, nested=(), map_entry=False):
    m = descriptor_pb2.DescriptorProto(name=name)
    for number, fname, ftype, label, type_name in fields:
        f = m.field.add(name=fname, number=number, type=ftype, label=label)
        if type_name:
            f.type_name = type_name
    for n in nested:
        m.nested_type.add().CopyFrom(n)
    if map_entry:
        m.options.map_entry = True
    return m


OPT, REP = F.LABEL_OPTIONAL, F.LABEL_REPEATED


def build_classes():
    fd = descriptor_pb2.FileDescriptorProto(name="rlrun_test_tensorboard.proto", package="tb",
                                            syntax="proto3",
                                            dependency=["google/protobuf/struct.proto"])
    fd.message_type.extend([
        message("TensorShapeProto", [(2, "dim", F.TYPE_MESSAGE, REP, ".tb.TensorShapeProto.Dim")],
                nested=[message("Dim", [(1, "size", F.TYPE_INT64, OPT, None)])]),
        message("TensorProto", [(1, "dtype", F.TYPE_INT32, OPT, None),
                                (2, "tensor_shape", F.TYPE_MESSAGE, OPT, ".tb.TensorShapeProto")]),
        message("SummaryMetadata", [
            (1, "plugin_data", F.TYPE_MESSAGE, OPT, ".tb.SummaryMetadata.PluginData")],
            nested=[message("PluginData", [(1, "plugin_name", F.TYPE_STRING, OPT, None),
                                           (2, "content", F.TYPE_BYTES, OPT, None)])]),
        message("Summary", [(1, "value", F.TYPE_MESSAGE, REP, ".tb.Summary.Value")], nested=[
            message("Image", [(1, "height", F.TYPE_INT32, OPT, None),
                              (2, "width", F.TYPE_INT32, OPT, None),
                              (3, "colorspace", F.TYPE_INT32, OPT, None),
                              (4, "encoded_image_string", F.TYPE_BYTES, OPT, None)]),
            message("Value", [(1, "tag", F.TYPE_STRING, OPT, None),
                              (2, "simple_value", F.TYPE_FLOAT, OPT, None),
                              (4, "image", F.TYPE_MESSAGE, OPT, ".tb.Summary.Image"),
                              (8, "tensor", F.TYPE_MESSAGE, OPT, ".tb.TensorProto"),
                              (9, "metadata", F.TYPE_MESSAGE, OPT, ".tb.SummaryMetadata")])]),
        message("Event", [(1, "wall_time", F.TYPE_DOUBLE, OPT, None),
                          (2, "step", F.TYPE_INT64, OPT, None),
                          (3, "file_version", F.TYPE_STRING, OPT, None),
                          (5, "summary", F.TYPE_MESSAGE, OPT, ".tb.Summary")]),
        message("SessionStartInfo", [
            (1, "hparams", F.TYPE_MESSAGE, REP, ".tb.SessionStartInfo.HparamsEntry"),
            (5, "start_time_secs", F.TYPE_DOUBLE, OPT, None)],
            nested=[message("HparamsEntry", [(1, "key", F.TYPE_STRING, OPT, None),
                                             (2, "value", F.TYPE_MESSAGE, OPT,
                                              ".google.protobuf.Value")], map_entry=True)]),
        message("SessionEndInfo", [(1, "status", F.TYPE_INT32, OPT, None),
                                   (2, "end_time_secs", F.TYPE_DOUBLE, OPT, None)]),
        message("HParamsPluginData", [
            (1, "version", F.TYPE_INT32, OPT, None),
            (3, "session_start_info", F.TYPE_MESSAGE, OPT, ".tb.SessionStartInfo"),
            (4, "session_end_info", F.TYPE_MESSAGE, OPT, ".tb.SessionEndInfo")]),
    ])
    pool = descriptor_pool.DescriptorPool()
    pool.AddSerializedFile(struct_pb2.DESCRIPTOR.serialized_pb)
    pool.Add(fd)
    factory = message_factory.MessageFactory(pool)
    return {name: factory.GetPrototype(pool.FindMessageTypeByName("tb." + name))
            for name in ("Event", "HParamsPluginData")}


CLASSES = build_classes()


def events(run_dir):
    files = sorted(glob.glob(os.path.join(run_dir, "events.out.tfevents.*")))
    if not files:
        raise ValueError(f"{run_dir}: no events.out.tfevents.* file")
    for path in files:
        for i, data in enumerate(records(path)):
            event = CLASSES["Event"].FromString(data)
            if i == 0 and event.file_version != "brain.Event:2":
                raise ValueError(f"{path}: first event is not file_version brain.Event:2")
            yield event


def read(run_dir):
    """scalars {tag: [(step, value)]}, hparams {name: value}, session end status or None,
    images {tag: (width, height, png bytes)}."""
    scalars, hparams, end, images = {}, {}, None, {}
    for event in events(run_dir):
        for value in event.summary.value:
            plugin = value.metadata.plugin_data
            if plugin.plugin_name == "hparams":
                data = CLASSES["HParamsPluginData"].FromString(plugin.content)
                if data.HasField("session_start_info"):
                    for key, v in data.session_start_info.hparams.items():
                        hparams[key] = getattr(v, v.WhichOneof("kind"))
                if data.HasField("session_end_info"):
                    end = data.session_end_info.status
            elif value.HasField("image"):
                images[value.tag] = (value.image.width, value.image.height,
                                     value.image.encoded_image_string)
            else:
                scalars.setdefault(value.tag, []).append((event.step, value.simple_value))
    return scalars, hparams, end, images


def check(run_dir, progress, finished):
    scalars, hparams, end, images = read(run_dir)
    with open(progress, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        raise ValueError(f"{progress} has no rows")
    steps = [int(float(r["time/total_timesteps"])) for r in rows]
    keys = [k for k in rows[0].keys() if k not in SB3_EXCLUDED]
    for tag in SB3_EXCLUDED:
        if tag in scalars:
            raise ValueError(f"{tag} is in TensorBoard, but SB3 keeps it out")
    for key in keys:
        expected = [(s, float(r[key])) for s, r in zip(steps, rows) if r[key] not in ("", None)]
        got = scalars.get(key, [])
        if [s for s, _ in got] != [s for s, _ in expected]:
            raise ValueError(f"{key}: steps {[s for s, _ in got][:20]}... in TensorBoard, "
                             f"{[s for s, _ in expected][:20]}... in progress.csv")
        for (s, v), (_, e) in zip(got, expected):
            # float32 in TensorBoard, 9 significant digits in the CSV: one float32 step apart.
            if not (abs(v - e) <= 2.0 ** -22 * abs(e) or v == e or (math.isnan(v) and math.isnan(e))):
                raise ValueError(f"{key} at step {s}: {v} in TensorBoard, {e} in progress.csv")
    extra = sorted(set(scalars) - set(keys) - {"final/ep_rew_mean", "final/eval_mean_reward"})
    if extra:
        raise ValueError(f"TensorBoard has tags progress.csv does not: {extra}")
    if not hparams or "algo.id" not in hparams or "run.seed" not in hparams:
        raise ValueError(f"the HParams session start lacks the config: {sorted(hparams)[:10]}")
    if finished:
        if end != 1:
            raise ValueError(f"session end status {end}, expected 1 (STATUS_SUCCESS)")
        if "final/ep_rew_mean" not in scalars:
            raise ValueError("no final/ep_rew_mean scalar")
    if "images/learning_curve" in images:
        width, height, png = images["images/learning_curve"]
        if not png.startswith(b"\x89PNG\r\n\x1a\n") or struct.unpack(">II", png[16:24]) != (width, height):
            raise ValueError("no learning-curve PNG of the size its Image message states")
    print(json.dumps({"rows": len(rows), "tags": len(keys), "hparams": len(hparams),
                      "algo": hparams.get("algo.id"), "last_step": steps[-1],
                      "session_end": end, "images": sorted(images),
                      "final": {t: scalars[t][-1][1] for t in scalars if t.startswith("final/")}}))


def main(argv):
    if len(argv) >= 3 and argv[1] == "check":
        try:
            check(argv[2], argv[3], "--finished" in argv[4:])
        except (ValueError, KeyError) as e:
            print(f"tfevents: {e}")
            return 1
        return 0
    if len(argv) == 3 and argv[1] == "dump":
        for event in events(argv[2]):
            print(json.dumps({"step": event.step, "wall_time": event.wall_time,
                              "tags": [v.tag for v in event.summary.value]}))
        return 0
    print(__doc__)
    return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv))
