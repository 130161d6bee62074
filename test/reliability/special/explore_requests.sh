#!/usr/bin/env bash
# Special reliability test: `dpend explore` (docs/explore.md) refuses hostile input in
# one line and stays up. The command line first (exit 2, one stderr line, nothing
# served); then the server, started by `dpend explore MAP.h5 --port 0` on a small flip
# map, gets one request per row below: each is refused with its HTTP status and one
# line naming the field, the same line is in the server's log, and afterwards a
# pixel still runs (200) and SIGTERM stops the server as Ctrl-C does (exit 0).
# The server is the Python package's: DPEND_PYTHON names an interpreter with dpend
# installed (CI: the venv of scripts/python_package.sh --keep); without one, skipped.
# Environment (set by the reliability runner): DPEND, ROOT, SCRATCH (the cwd).
# Exit 0: pass, 77: skipped, other: fail.
. "$ROOT/test/reliability/lib.sh"
py="${DPEND_PYTHON:-}"
if [[ -z "$py" ]] || ! "$py" -c 'import dpend.explore' 2> /dev/null; then
  echo "SKIP explore_requests: DPEND_PYTHON does not name a python with dpend installed"
  exit 77
fi
export DPEND_PYTHON="$py"
pass() { printf 'ok   %s\n' "$1"; }

"$DPEND" sweep --n 16 --t-end 10 --output map.h5 --quiet > /dev/null 2>&1 ||
  { echo "FAIL sweep for the map"; exit 1; }
"$DPEND" simulate --t-end 0.1 --output sim.h5 --quiet > /dev/null 2>&1 ||
  { echo "FAIL simulate"; exit 1; }

# -- the command line: ID, the field its one line names, the arguments
cli() {
  local id=$1 field=$2; shift 2
  timeout 20 "$DPEND" explore "$@" > "cli_$id.out" 2> "cli_$id.err"
  local st=$? lines
  lines=$(wc -l < "cli_$id.err")
  if [[ $st -eq 2 && $lines -eq 1 ]] && grep -qiF -- "$field" "cli_$id.err" &&
     [[ ! -s "cli_$id.out" ]]; then
    pass "cli $id"
  else
    bad "cli $id: exit $st, stderr $(head -c 300 "cli_$id.err")"
  fi
}
cli no_map       "MAP.h5 is missing"
cli port_range   "--port '99999'"   map.h5 --port 99999
cli port_token   "--port '80x'"     map.h5 --port 80x
cli port_twice   "--port"           map.h5 --port 1 --port 2
cli host         "--host 'a;b'"     map.h5 --host 'a;b'
cli max_runs     "--max-runs '0'"   map.h5 --max-runs 0
cli unknown      "--t-end"          map.h5 --t-end 5
cli two_maps     "a second map"     map.h5 map.h5
cli missing      "nothere.h5"       nothere.h5
cli not_a_map    "no group /sweep"  sim.h5
cli a_folder     "not a readable"   .

# -- the server
"$DPEND" explore map.h5 --port 0 > server.out 2> server.log &
server=$!
url=""
for _ in $(seq 1 100); do
  url=$(grep -o 'http://127\.0\.0\.1:[0-9]*/' server.out 2> /dev/null | head -n 1)
  [[ -n "$url" ]] && break
  kill -0 "$server" 2> /dev/null || break
  sleep 0.2
done
if [[ -z "$url" ]]; then
  echo "FAIL the server did not start: $(head -c 300 server.log)"
  kill "$server" 2> /dev/null
  exit 1
fi
grep -q 'this machine only' server.out && pass "binds to 127.0.0.1 and says so" ||
  bad "the address line: $(cat server.out)"

# one request: METHOD URL [HOST] -> "STATUS<TAB>BODY" (the body's lines joined by \n)
request() {
  "$py" - "$1" "$2" "${3:-}" << 'EOF'
import sys, urllib.error, urllib.request
method, url, host = sys.argv[1], sys.argv[2], sys.argv[3]
headers = {"Host": host} if host else {}
try:
    with urllib.request.urlopen(urllib.request.Request(url, method=method, headers=headers),
                                timeout=60) as r:
        status, body = r.status, r.read()
except urllib.error.HTTPError as e:
    status, body = e.code, e.read()
text = body.decode("utf-8", "replace")
print(f"{status}\t{text!r}")
EOF
}

# ID, HTTP status, the field the one line names, the request (path and query)
row() {
  local id=$1 status=$2 field=$3 path=$4 method=${5:-GET} host=${6:-} got code body
  got=$(request "$method" "${url%/}$path" "$host")
  code=${got%%$'\t'*}
  body=${got#*$'\t'}
  # one line: the body is 'LINE\n' (repr), no other newline
  if [[ "$code" == "$status" ]] && [[ "$body" == *"$field"* ]] &&
     [[ $(grep -o '\\n' <<< "$body" | wc -l) -eq 1 ]] &&
     grep -F "refused $method" server.log | grep -qF -- "$field"; then
    pass "request $id"
  else
    bad "request $id: $code $body"
  fi
}
row nan_pixel     400 "i = 'nan'"           "/api/pixel?i=nan&j=3"
row inf_pixel     400 "j = 'inf'"           "/api/pixel?i=1&j=inf"
row float_pixel   400 "i = '1.5'"           "/api/pixel?i=1.5&j=3"
row negative      400 "i = '-1'"            "/api/pixel?i=-1&j=3"
row outside       400 "[0, 15]"             "/api/pixel?i=16&j=0"
row huge_index    400 "j = '9999999999'"    "/api/pixel?i=0&j=9999999999"
row huge_t_end    400 "t_end = '1e308'"     "/api/pixel?i=1&j=1&t_end=1e308"
row tiny_dt       400 "dt = '1e-300'"       "/api/pixel?i=1&j=1&dt=1e-300"
row twice         400 "i is given twice"    "/api/pixel?i=1&j=1&i=2"
row missing_j     400 "j is missing"        "/api/pixel?i=1"
row long_query    400 "characters"          "/api/pixel?i=1&j=1&x=$(printf 'a%.0s' {1..700})"
row bad_utf8      400 "is not key=value"    "/api/pixel?i=%ff&j=1"
row path          404 "is not served"       "/../../etc/passwd"
row path_encoded  404 "is not served"       "/%2e%2e/%2e%2e/etc/passwd"
row map_param     400 "map = '/etc/passwd'" "/api/map?map=/etc/passwd"
row values_path   400 "name = '/etc/passwd'" "/api/values?name=/etc/passwd"
row download      400 "i = 'x'"             "/api/run.h5?i=x&j=1"
row post          405 "method POST"         "/api/pixel?i=1&j=1" POST
row other_host    403 "Host 'evil.example"  "/api/map" GET "evil.example"

# a line end in a value is escaped: no forged line in the log
got=$(request GET "${url%/}/api/pixel?i=1%0Adpend%20explore:%20forged&j=1")
if [[ "${got%%$'\t'*}" == 400 ]] && ! grep -q '^dpend explore: forged' server.log &&
   ! grep -v '^dpend explore: ' server.log | grep -q .; then
  pass "a line end in a value stays escaped in its one line"
else
  bad "a line end in a value: ${got:0:200}; log: $(tail -n 3 server.log)"
fi
got=$(request GET "${url%/}/api/pixel?i=3&j=5")
[[ "${got%%$'\t'*}" == 200 ]] && pass "the server is up: a pixel runs after the refusals" ||
  bad "a pixel after the refusals: ${got:0:300}"
kill -TERM "$server"
wait "$server"
st=$?
[[ $st -eq 0 ]] && grep -q 'stopped' server.log && pass "SIGTERM stops it (exit 0)" ||
  bad "SIGTERM: exit $st, $(tail -n 2 server.log)"
finish
