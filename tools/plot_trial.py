#!/usr/bin/python3
"""Draws a recorded trial path (`contacts trial ... --record PATH.csv`) as a PNG:
insertion depth z(t), the part's distance off its assembled axis, and the
force rendered to the hand. Also prints a Markdown table every `--every` s.

    /usr/bin/python3 tools/plot_trial.py PATH.csv docs/images/haptics_motor_axis.png
"""
import argparse
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

from PIL import Image, ImageDraw  # noqa: E402

from contactwb import trial  # noqa: E402


def panel(draw, box, xs, ys, colour, label, unit, x_max):
    left, top, right, bottom = box
    draw.rectangle(box, outline=(160, 160, 160))
    y_min, y_max = min(ys + [0.0]), max(ys + [0.0])
    if y_max - y_min < 1e-12:
        y_max = y_min + 1.0
    def to_px(x, y):
        return (left + (right - left) * x / x_max, bottom - (bottom - top) * (y - y_min) / (y_max - y_min))
    if y_min < 0 < y_max:
        draw.line([to_px(0, 0), to_px(x_max, 0)], fill=(210, 210, 210))
    draw.line([to_px(x, y) for x, y in zip(xs, ys)], fill=colour, width=2)
    draw.text((left + 6, top + 4), f"{label} [{unit}]  min {min(ys):.4g}  max {max(ys):.4g}", fill=(0, 0, 0))
    for k in range(int(x_max) + 1):
        x, _ = to_px(k, y_min)
        draw.line([(x, bottom), (x, bottom + 4)], fill=(0, 0, 0))
        draw.text((x - 3, bottom + 6), str(k), fill=(0, 0, 0))


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("path")
    parser.add_argument("png")
    parser.add_argument("--every", type=float, default=0.25)
    args = parser.parse_args()
    samples = trial.read_path(args.path)
    t = [s["t"] for s in samples]
    z = [s["translate"][2] for s in samples]
    off = [math.hypot(s["translate"][0], s["translate"][1]) for s in samples]
    tilt = [math.hypot(s["rotate_deg"][0], s["rotate_deg"][1]) for s in samples]
    force = [math.sqrt(sum(f * f for f in s["force"])) for s in samples]
    width, height = 900, 640
    image = Image.new("RGB", (width, height), "white")
    draw = ImageDraw.Draw(image)
    draw.text((20, 8), f"Haptic trial: {os.path.basename(args.path)} (time in s)", fill=(0, 0, 0))
    x_max = max(t) if t else 1.0
    rows = [("axial offset z", z, (30, 90, 200), "mm"), ("lateral offset of the centre", off, (200, 60, 30), "mm"),
            ("tilt", tilt, (120, 40, 160), "deg"), ("force to the hand", force, (30, 150, 60), "N")]
    for i, (label, ys, colour, unit) in enumerate(rows):
        top = 30 + i * 150
        panel(draw, (60, top, width - 20, top + 120), t, ys, colour, label, unit, x_max)
    image.save(args.png)
    print("| t (s) | translate (mm) | rotate (deg) | force (N) | engaged | penetration (mm) |")
    print("|---|---|---|---|---|---|")
    next_t = 0.0
    for s in samples:
        if s["t"] + 1e-9 >= next_t or s is samples[-1]:
            print(f"| {s['t']:.2f} | {', '.join(f'{v:.3f}' for v in s['translate'])} | "
                  f"{', '.join(f'{v:.3f}' for v in s['rotate_deg'])} | "
                  f"{math.sqrt(sum(f * f for f in s['force'])):.3f} | {'yes' if s['engaged'] else 'no'} | "
                  f"{s['penetration']:.4f} |")
            next_t += args.every


if __name__ == "__main__":
    main()
