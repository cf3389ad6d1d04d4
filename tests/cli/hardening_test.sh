#!/usr/bin/env bash
# Hostile inputs: each is refused cleanly and quickly - exit 2 with a message naming the file,
# never a crash (134 abort, 139 SIGSEGV), a hang (124 from timeout), a blown memory limit or a
# raw library text. Big inputs are generated here. Usage: hardening_test.sh VMT SRC OUT
set -u
vmt=$1 src=$2 out=$3
rm -rf "$out" && mkdir -p "$out"
# 2 GB of address space: every refusal here must come before a big allocation. A sanitizer's
# shadow memory needs terabytes of address space: no limit there.
bad_vm_limit=2000000
# gcc links the runtime as a shared library, clang into the executable.
if ldd "$vmt" 2>/dev/null | grep -q 'lib[at]san' || nm -D "$vmt" 2>/dev/null | grep -q ' __[at]san_init$'; then
  bad_vm_limit=unlimited
fi
bad_timeout=20
. "$(dirname "$0")/refusal_checks.sh"

model=$src/models/lathe-c1/machine.yaml
scene() {  # scene FILE EXTRA_YAML: a small valid scene on lathe-c1 plus EXTRA_YAML
  printf 'scene: hardening\nmodel: %s\nbackend: kinematic\nduration: 0.1\n%s' "$2" "$3" >"$1"
}

# Deeply nested URDF: urdfdom recursed per element and overflowed the stack.
mkdir -p "$out/deep_urdf"
cp -r "$src/models/lathe-c1/." "$out/deep_urdf/"
python3 -c "print('<robot name=\"r\">\n' + '<a>' * 50000 + '</a>' * 50000 + '</robot>')" \
  >"$out/deep_urdf/machine.urdf"
bad urdf_deep_signals "machine.urdf:2: elements nested deeper than 100 levels" -- \
  "$vmt" signals "$out/deep_urdf/machine.yaml"
scene "$out/urdf_deep.yaml" "$out/deep_urdf/machine.yaml" ""
bad urdf_deep_run "machine.urdf:2: elements nested deeper than 100" -- "$vmt" run "$out/urdf_deep.yaml" --out "$out/o"

# Deeply nested YAML: flow collections in a scene, block mappings in a model.
python3 -c "print('scene: x\nmodel: ' + '[' * 100000 + ']' * 100000)" >"$out/deep_flow.yaml"
bad yaml_deep_flow "deep_flow.yaml:2: nesting deeper than 100 levels" -- "$vmt" run "$out/deep_flow.yaml" --out "$out/o"
python3 -c "print('machine: x\nio:\n' + ''.join(' ' * (i + 1) + 'a:\n' for i in range(5000)))" \
  >"$out/deep_block.yaml"
bad yaml_deep_block "deep_block.yaml:[0-9]+: nesting deeper than 100 levels" -- "$vmt" signals "$out/deep_block.yaml"

# A 10 MB flow list under an unknown key: refused before yaml-cpp builds its tree (2.4 GB).
python3 -c "print('scene: x\nmodel: m.yaml\nbogus: [' + ','.join(['1'] * 5000000) + ']')" >"$out/big_list.yaml"
bad yaml_big_list "big_list.yaml: more than 200000 YAML nodes" -- "$vmt" run "$out/big_list.yaml" --out "$out/o"
head -c 17000000 /dev/zero | tr '\0' '#' >"$out/huge.yaml"
bad yaml_huge_file "huge.yaml: cannot open file: the file is 17000000 bytes, more than the limit" -- \
  "$vmt" run "$out/huge.yaml" --out "$out/o"

# Gateway values of the wrong type's range: one check for constants, timeline steps and --set.
probe_scene() {  # probe_scene FILE CONSTANTS TIMELINE
  printf 'scene: c\nmodel: %s\nbackend: kinematic\nduration: 0.1\nnc:\n  program: %s\n%s%s' \
    "$model" "$src/scenes/nc/stepped_shaft.mtc" "$2" "$3" >"$1"
}
probe_scene "$out/const_range.yaml" "plc:
  program: probe_block
  constants: {QMFB1A00.ACHS_NR_1: 40000}
" ""
bad int_constant_range "const_range.yaml:[0-9]+:[0-9]+: plc.constants.QMFB1A00.ACHS_NR_1: .*40000 is outside INT's range -32768..32767" -- \
  "$vmt" run "$out/const_range.yaml" --out "$out/o"
probe_scene "$out/const_frac.yaml" "plc:
  program: probe_block
  constants: {QMFB1A00.ACHS_NR_1: 1.5}
" ""
bad int_constant_fraction "const_frac.yaml:[0-9]+:[0-9]+: plc.constants.QMFB1A00.ACHS_NR_1: .*1.5 is not an integer: INT" -- \
  "$vmt" run "$out/const_frac.yaml" --out "$out/o"
probe_scene "$out/step_range.yaml" "" "timeline:
  - signal: {name: QMFB1A00.ACHS_NR_1, value: 40000}
"
bad int_step_range "step_range.yaml:[0-9]+:[0-9]+: timeline\[0\].signal.value: .*40000 is outside INT's range" -- \
  "$vmt" run "$out/step_range.yaml" --out "$out/o"
probe_scene "$out/step_frac.yaml" "" "timeline:
  - signal: {name: QMFB1A00.ACHS_NR_1, value: 1.5}
"
bad int_step_fraction "step_frac.yaml:[0-9]+:[0-9]+: timeline\[0\].signal.value: .*1.5 is not an integer" -- \
  "$vmt" run "$out/step_frac.yaml" --out "$out/o"
probe_scene "$out/set.yaml" "" ""
bad int_set_range "QMFB1A00.ACHS_NR_1.*40000 is outside INT's range" -- \
  "$vmt" run "$out/set.yaml" --set QMFB1A00.ACHS_NR_1=40000 --out "$out/o"

# Geometric sizes beyond a lathe's: 1e308 made the mesh code loop ("eigen: too many iterations").
scene "$out/huge_diameter.yaml" "$model" "workpiece: {diameter: 1e308, length: 100, z: 60}
"
bad huge_diameter "huge_diameter.yaml:[0-9]+:[0-9]+: workpiece.diameter: must be in" -- \
  "$vmt" run "$out/huge_diameter.yaml" --out "$out/o"
scene "$out/big_diameter.yaml" "$model" "workpiece: {diameter: 5000, length: 100, z: 60}
"
bad big_diameter "big_diameter.yaml:[0-9]+:[0-9]+: workpiece.diameter: must be in \(0, 2000\] mm" -- \
  "$vmt" run "$out/big_diameter.yaml" --out "$out/o"
scene "$out/huge_section.yaml" "$model" "workpiece:
  z: 60
  sections:
    - {from: 0, to: 100, diameter: 60, bore: 1e20}
"
bad huge_bore "huge_section.yaml:[0-9]+:[0-9]+: workpiece.sections\[0\].bore" -- \
  "$vmt" snapshot "$out/huge_section.yaml" --at 0 --out "$out/o.png"

mkdir -p "$out/far_vertex"
cp -r "$src/models/lathe-c1/." "$out/far_vertex/"
# The first vertex after the header, its position far away.
sed -i '/^end_header/{n;s/^[^ ]* [^ ]* [^ ]*/1e200 1e200 1e200/}' \
  "$out/far_vertex/meshes/turret_st01_insert.ply"
bad far_vertex "turret_st01_insert.ply: a vertex lies beyond \+-100 m of its link" -- \
  "$vmt" signals "$out/far_vertex/machine.yaml"

# FIFOs and directories: opening a FIFO waited forever for a writer.
mkfifo "$out/fifo.yaml" "$out/fifo.mtc" "$out/fifo.png" "$out/fifo.urdf"
bad fifo_scene "fifo.yaml: cannot open file: not a regular file" -- "$vmt" run "$out/fifo.yaml" --out "$out/o"
scene "$out/fifo_model.yaml" "$out/fifo.yaml" ""
bad fifo_model "fifo_model.yaml:[0-9]+:[0-9]+: model: cannot open model .*fifo.yaml: not a regular file" -- "$vmt" run "$out/fifo_model.yaml" --out "$out/o"
bad fifo_nc_check "fifo.mtc:0:0: error: cannot open file: not a regular file" -- "$vmt" check "$out/fifo.mtc"
scene "$out/fifo_nc.yaml" "$model" "nc: {program: $out/fifo.mtc}
"
bad fifo_nc_scene "nc.program: cannot open NC program .*fifo.mtc: not a regular file" -- \
  "$vmt" run "$out/fifo_nc.yaml" --out "$out/o"
bad fifo_png "fifo.png.*not a regular file" -- "$vmt" imgdiff "$out/fifo.png" "$out/fifo.png"
mkdir -p "$out/fifo_urdf"
cp -r "$src/models/lathe-c1/." "$out/fifo_urdf/"
sed -i "s#^urdf: .*#urdf: $out/fifo.urdf#" "$out/fifo_urdf/machine.yaml"
bad fifo_urdf "fifo.urdf: cannot open URDF file: not a regular file" -- "$vmt" signals "$out/fifo_urdf/machine.yaml"
mkdir -p "$out/fifo_mesh"
cp -r "$src/models/lathe-c1/." "$out/fifo_mesh/"
mesh=$(ls "$out/fifo_mesh/meshes" | head -1)
rm "$out/fifo_mesh/meshes/$mesh" && mkfifo "$out/fifo_mesh/meshes/$mesh"
bad fifo_mesh "$mesh: cannot open file: not a regular file" -- "$vmt" signals "$out/fifo_mesh/machine.yaml"
bad dir_scene "$out: cannot open file: Is a directory" -- "$vmt" run "$out" --out "$out/o"
scene "$out/empty_model.yaml" '""' ""
bad empty_model "empty_model.yaml:[0-9]+:[0-9]+: model: cannot open model .*: Is a directory" -- "$vmt" run "$out/empty_model.yaml" --out "$out/o"
bad dir_png "'$out': Is a directory" -- "$vmt" imgdiff "$out" "$out"
bad missing_png "nope.png': No such file or directory" -- "$vmt" imgdiff "$out/nope.png" "$out/nope.png"
# A study's subroutine is checked when the plan loads, before the reference run.
sed 's#^  subroutines: .*#  subroutines: [""]#; s#\.\./models#'"$src"'/models#; s#program: nc/#program: '"$src"'/scenes/nc/#' \
  "$src/scenes/study-repos-turning.yaml" >"$out/study_empty_sub.yaml"
bad study_empty_subroutine "study.subroutines\[0\]: cannot open NC program .*: Is a directory" -- \
  timeout "$bad_timeout" "$vmt" study repos "$out/study_empty_sub.yaml" --out "$out/study"

# PNG bombs: a 200-byte file may claim 16384 x 16384 pixels (1 GiB to allocate).
python3 - "$out/bomb.png" <<'PY'
import struct, sys, zlib
def chunk(kind, data):
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", 16384, 16384, 8, 6, 0, 0, 0))
png += chunk(b"IDAT", zlib.compress(b"\0" * 1000)) + chunk(b"IEND", b"")
open(sys.argv[1], "wb").write(png)
PY
bad png_bomb_header "bomb.png.*larger than the limit of 33554432 pixels" -- "$vmt" imgdiff "$out/bomb.png" "$out/bomb.png"

echo "hardening: $passes passed, $fails failed"
[ "$fails" -eq 0 ]
