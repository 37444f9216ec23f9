#!/usr/bin/env bash
# Installs the Debian 12 packages lagrange needs. A no-op (no apt-get call at
# all) when everything is already present.
#   scripts/setup.sh          everything: build, run, the test suite, benchmarks
#   scripts/setup.sh --run    only what building the programs and running a
#                             scenario with its report needs (scripts/demo.sh)
set -euo pipefail

# Building the five programs and running one scenario with --report.
run_packages=(
  build-essential cmake pkg-config
  liblcm-dev liblcm-bin libglib2.0-dev  # LCM and lcm-gen
  gnuplot-nox  # lagrange report's plots
  liburdfdom-dev liborocos-kdl-dev  # URDF arms: the document, the dynamics
  libsodium-dev libssl-dev  # each run's random key; every message's HMAC-SHA256 (libcrypto)
  libhdf5-dev  # lagrange export: HDF5 through its C++ API (H5Cpp)
  # the second physics engine; its CMake package names qhull's headers and
  # looks for OpenGL (find_dependency), which lagrange itself never calls
  libmujoco-dev libqhull-dev libgl-dev libopengl-dev libglx-dev
  libode-dev libeigen3-dev libspdlog-dev libyaml-cpp-dev libcli11-dev nlohmann-json3-dev
  libcpp-httplib-dev libjs-three  # lagrange view: its HTTP server, three.js for its page
  libnlopt-cxx-dev  # lagrange tune: derivative-free bounded search (NLopt's C++ API)
  iproute2 util-linux  # each run's private network namespace
)
# Everything else: the Java message classes (lcm-spy), the test suite, the
# benchmarks, the fuzzers.
more_packages=(
  git liblcm-java libjchart2d-java default-jdk-headless
  # python/lagrange, its tests (standard library only) and `pip install ./python`
  python3 python3-venv python3-pip python3-setuptools python3-wheel
  python3-h5py  # lagrange export's test reads the file back as a user would
  # examples/notebooks/first_figure.ipynb, executed by its test as a student would
  python3-numpy python3-matplotlib jupyter-nbconvert python3-ipykernel
  libgtest-dev libbenchmark-dev
  # lagrange spy (lcm-spy's window) and its test: a virtual display, a
  # screenshot, OCR of it
  default-jre fonts-dejavu-core xvfb imagemagick tesseract-ocr tesseract-ocr-eng
  # lagrange sweep --slurm's test: a one-node cluster started inside the
  # test's network namespace. Installing them starts no Slurm daemon (without
  # systemd invoke-rc.d declines; with it they find no /etc/slurm/slurm.conf);
  # under systemd munge's own service may start, on a local socket only.
  munge slurmctld slurmd slurm-client
  # lagrange view's test drives headless chromium through chromedriver and
  # reads the screenshots
  chromium chromium-driver libpng-dev
  # scripts/fuzz.sh: libFuzzer with clang
  clang libclang-rt-14-dev
)

case "${1:-}" in
  "") packages=("${run_packages[@]}" "${more_packages[@]}") ;;
  --run) packages=("${run_packages[@]}") ;;
  *)
    echo "setup: error: unknown argument '$1'; expected none (everything) or --run" >&2
    exit 2
    ;;
esac

missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
  [[ "$status" == "install ok installed" ]] || missing+=("$p")
done

if ((${#missing[@]} == 0)); then
  exit 0
fi

echo "setup: installing missing Debian packages: ${missing[*]}"
if [[ $(id -u) -eq 0 ]]; then
  as_root=()
elif command -v sudo >/dev/null; then
  as_root=(sudo)
else
  echo "setup: error: packages missing (${missing[*]}) and neither root nor sudo is available;" \
    "install them as root with: apt-get install ${missing[*]}" >&2
  exit 1
fi
export DEBIAN_FRONTEND=noninteractive
"${as_root[@]}" apt-get update -qq
"${as_root[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "setup: done"
