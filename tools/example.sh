#!/usr/bin/env bash
# The main job: set up, then build the quaternion example (paper Listing 1) and simulate it.
# rfc build generates the whole system (VHDL, Vivado and HLS scripts, ROS 2 node, report);
# rfc sim replays 200 random orientations through the generated logic (Verilator; GHDL with --simulator ghdl) and writes the
# Euler angles; the last step compares them with the accelerator's Python reference.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/tools/setup.sh"
cd "$root"
example=examples/quaternion_to_euler
out=${RFC_EXAMPLE_OUT:-build/quaternion_to_euler}
mkdir -p "$out"
.venv/bin/rfc build "$example/project.yaml" -o "$out/system"
.venv/bin/python "$example/make_bags.py" random 200 "$out/orientations.mcap"
.venv/bin/rfc sim "$example/project.yaml" --bag "$out/orientations.mcap" --out "$out/euler.mcap" \
    --drain-cycles 300
.venv/bin/python "$example/compare.py" "$out/orientations.mcap" "$out/euler.mcap"
echo "example: the system is in $out/system (see report.md); the angles in $out/euler.mcap"
