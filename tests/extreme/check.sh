# The outcome check shared by sweep.sh and sweep_models.sh (source it after
# setting $out, $err and $TIMEOUT): a run ends with exit 0 and finite rows, or
# exit 1 with one error line, or exit 2 with one line naming an option; never
# a timeout. EXPECTED is any, a code, or CODE:OPTION (the line names --OPTION).
check() { # check LABEL EXPECTED CODE CMD: prints the outcome, returns 1 on a violation
  local label=$1 expected=$2 code=$3 cmd=$4 lines why=""
  lines=$(wc -l <"$err")
  case $code in
  0)
    [[ -s $err ]] && why="stderr not empty"
    grep -v '^#' "$out" | tail -n +2 | grep -qi 'inf\|nan' && why="inf/nan in the rows"
    grep '^# pre ' "$out" | grep -qi 'inf\|nan' && why="inf/nan in the pre line"
    [[ $(grep -vc '^#' "$out") -ge 2 ]] || why="no rows" ;;
  1) [[ $lines == 1 ]] && grep -q "^mdrmap $cmd: error: " "$err" || why="not one error line" ;;
  2)
    [[ $lines == 1 ]] && grep -Eq "^mdrmap $cmd: error: --[A-Za-z0-9-]+: " "$err" ||
      why="not one line naming an option"
    [[ -s $out ]] && why="stdout not empty" ;;
  124 | 137) why="timeout (${TIMEOUT} s): ran unbounded" ;;
  *) why="exit $code" ;;
  esac
  if [[ -z $why && $expected != any ]]; then
    [[ ${expected%%:*} == "$code" ]] || why="exit $code, expected $expected"
    [[ $expected == *:* ]] && ! grep -q -- "--${expected#*:}:" "$err" && why="does not name --${expected#*:}"
  fi
  [[ -z $why ]] && return 0
  echo "FAIL: $label: $why: $(head -c 300 "$err")"
  return 1
}
