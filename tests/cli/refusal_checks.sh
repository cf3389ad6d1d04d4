# Sourced by the command-line tests of bad input: `bad` runs a command that must be refused
# cleanly. Set before sourcing: out (the folder for logs); optionally bad_timeout (s, default
# 60) and bad_vm_limit (ulimit -v in KiB, default unlimited). Counts into fails and passes.
fails=0 passes=0
# Library and runtime texts a user must never see in place of a message.
raw='basic_filebuf|terminate called|what\(\)|std::|yaml-cpp|bad file|Segmentation|Aborted|bad_alloc|json\.exception|filesystem error|stoi|invalid node|bad conversion|At Most|not in range'
bad() {  # bad NAME PATTERN -- command...: exit 2 in time, PATTERN in the output, no raw text
  local name=$1 pattern=$2; shift 3
  local log="$out/$name.log"
  (ulimit -v "${bad_vm_limit:-unlimited}"; timeout "${bad_timeout:-60}" "$@") >"$log" 2>&1 </dev/null
  local got=$?
  if [ "$got" != 2 ]; then
    echo "FAIL $name: exit $got, wanted 2"; sed 's/^/    /' "$log" | head -10; fails=$((fails+1)); return
  fi
  if ! grep -qE -- "$pattern" "$log"; then
    echo "FAIL $name: output lacks /$pattern/"; sed 's/^/    /' "$log" | head -10; fails=$((fails+1)); return
  fi
  if grep -qE -- "$raw" "$log"; then
    echo "FAIL $name: raw library text"; sed 's/^/    /' "$log" | head -10; fails=$((fails+1)); return
  fi
  echo "ok   $name"; passes=$((passes+1))
}
