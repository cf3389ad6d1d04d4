#!/usr/bin/env bash
# Installs the Debian 12 packages vmt builds with. Idempotent: quiet when all are there.
set -euo pipefail
packages=(
  g++ cmake ninja-build pkg-config git
  libbullet-dev libfcl-dev libccd-dev libassimp-dev libeigen3-dev
  libosmesa6-dev libpng-dev libyaml-cpp-dev liburdfdom-dev libcli11-dev nlohmann-json3-dev
  libgtest-dev libbenchmark-dev libmodbus-dev
  # pymodbus 3.0 imports serial_asyncio even for TCP; Debian only recommends it.
  python3 python3-pymodbus python3-serial-asyncio mbpoll
  # tests/cli/bad_inputs.py reads the scene and machine files to vary them.
  python3-yaml
  # vmt study shards on one machine without Slurm (tests/cli/study_test.sh uses it if there).
  parallel
  # vmt study sbatch on a real Slurm cluster (tests/cli/slurm_test.sh starts a single-node one).
  munge slurmctld slurmd slurm-client
  clang libclang-rt-14-dev
  # The operator station (vmt serve --http): its HTTP server, the page's three.js and Chart.js,
  # and the headless browser its tests drive.
  libcpp-httplib-dev libjs-three libjs-chart.js
  chromium chromium-driver python3-selenium
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  SUDO=""; [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
