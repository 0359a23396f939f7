#!/usr/bin/env bash
# The main job: set up, then run rfc on the bundled example.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/tools/setup.sh"
cd "$root"
.venv/bin/rfc msg show geometry_msgs/Quaternion --middleware ros2
.venv/bin/rfc msg show franka_msgs/FrankaState --msg-path examples/franka/msg --include 'q' --include 'O_T_EE'
