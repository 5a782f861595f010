"""Reads a run folder's TensorBoard event files with TensorBoard's own readers and prints one
JSON object: per file its name and first event's file_version; every scalar event as
[tag, step, value] in file order (EventFileLoader: the raw records); every text summary as
[tag, step, text]; and per tag the steps TensorBoard's EventAccumulator would show.

Usage: python read-tensorboard.py RUN_DIR  (tests/tensorboard.rs runs it in the venv that
scripts/python-env.sh makes from scripts/requirements-tensorboard.txt)."""

import json
import os
import sys

from tensorboard.backend.event_processing import event_accumulator, event_file_loader
from tensorboard.util import tensor_util

run = sys.argv[1]
files = sorted(f for f in os.listdir(run) if "tfevents" in f)
out = {"files": [], "scalars": [], "texts": [], "shown": {}}
for name in files:
    first = None
    for event in event_file_loader.LegacyEventFileLoader(os.path.join(run, name)).Load():
        if first is None:
            first = event.file_version
        for value in event.summary.value:
            kind = value.WhichOneof("value")
            if kind == "simple_value":
                out["scalars"].append([value.tag, event.step, value.simple_value])
            elif kind == "tensor" and value.metadata.plugin_data.plugin_name == "text":
                text = tensor_util.make_ndarray(value.tensor).item().decode("utf-8")
                out["texts"].append([value.tag, event.step, text])
    out["files"].append({"name": name, "file_version": first})

acc = event_accumulator.EventAccumulator(run, size_guidance={event_accumulator.SCALARS: 0})
acc.Reload()
for tag in acc.Tags()["scalars"]:
    out["shown"][tag] = [[s.step, s.value] for s in acc.Scalars(tag)]
print(json.dumps(out))
