"""Writes the training cameras of a training log as the original trainer's cameras.json
(reference §1.2: position = camera centre, rotation = camera-to-world R^T), so that a PLY of
the log's last snapshot and this file form a scene file with cameras for `vis4gs view`.

Usage: LogCamerasJson.py LOG.h5 OUTPUT.json
"""
import json
import os
import sys

import h5py
import numpy as np


def main(log_path, output):
    with h5py.File(log_path, "r") as log:
        cameras = log["cameras"]
        entries = []
        for i, name in enumerate(cameras["name"][()]):
            if int(cameras["split"][i]) != 0:
                continue
            w2c = np.array(cameras["world_to_camera"][i])
            rotation, translation = w2c[:3, :3], w2c[:3, 3]
            entries.append({
                "id": len(entries),
                "img_name": name.decode() if isinstance(name, bytes) else str(name),
                "width": int(cameras["width"][i]),
                "height": int(cameras["height"][i]),
                "position": (-rotation.T @ translation).tolist(),
                "rotation": rotation.T.tolist(),
                "fx": float(cameras["fx"][i]),
                "fy": float(cameras["fy"][i]),
            })
    os.makedirs(os.path.dirname(os.path.abspath(output)), exist_ok=True)
    with open(output, "w") as f:
        json.dump(entries, f)
    print(f"wrote {len(entries)} training cameras to {output}")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit("usage: LogCamerasJson.py LOG.h5 OUTPUT.json")
    main(sys.argv[1], sys.argv[2])
