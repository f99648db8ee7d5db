#!/usr/bin/env bash
# Regenerates the shipped multi-intersection SUMO scenarios (sumo_data/grid4x4,
# sumo_data/arterial4x4; scenarios/*.yaml name them) with SUMO's own tools: netgenerate /
# netconvert for the networks, randomTrips.py (--validate routes them with duarouter) for one
# hour of demand, and a peak variant whose demand rises to twice the base rate in the middle of
# the hour. Fixed seeds: running it again gives the same files. The outputs are committed; this
# script documents how they were made and is not part of the build.
#
#   grid4x4      16 signalised 4-arm junctions 200 m apart, 2 lanes + a left-turn lane per
#                approach, 50 km/h; every light has netconvert's 4 green phases (through with
#                permissive left, protected left, for N-S and E-W). ~3000 vehicles/h from the
#                16 fringe roads (RESCO's grid4x4 has the same shape).
#   arterial4x4  4 east-west arterials (3 lanes + left-turn lane, 60 km/h) crossing 4
#                north-south streets (1 lane, 40 km/h) 250 m apart, 16 lights; demand weighted
#                by lanes, so most of it runs along the arterials (RESCO's arterial4x4 idea).
#   random25     an irregular network (netgenerate --rand: junctions of 2-6 roads at random
#                distances, 2 lanes, 50 km/h) with netconvert's guessed and joined lights: 25
#                lights of 2 to 6 greens and 8 to 36 links; 07:00-08:00 (begin 25200), about
#                3070 vehicles with a peak in the middle of the hour (2250 -> 4500 -> 2250/h).
#   spider15     a spider web (netgenerate --spider: 5 arms, 3 rings 150 m apart): 15 lights,
#                rings of 3-green five-way ... and 2-green outer junctions; 07:00-08:00, about
#                2500 vehicles with a peak (1800 -> 3600 -> 1800/h).
# The two irregular ones check that nothing was fitted to regular grids; their lights are
# netconvert's own programs (fixed-time is weak there, as on many imported city networks).
set -euo pipefail
cd "$(dirname "$0")/../.."
export SUMO_HOME=${SUMO_HOME:-/usr/share/sumo}
TOOLS=$SUMO_HOME/tools
PY=${PYTHON:-/usr/bin/python3}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# Without the generators' comments (temporary paths) and the schema reference: a route file
# that names an XML schema is validated by default, which fails without SUMO_HOME.
strip_route_file() {  # path
  "$PY" - "$1" <<'STRIP'
import re, sys
path = sys.argv[1]
text = open(path).read()
text = re.sub(r"<!--.*?-->\s*", "", text, flags=re.S)
text = re.sub(r'<routes [^>]*>', "<routes>", text, count=1)
open(path, "w").write(text)
STRIP
}

make_demand() {  # net dir name period-list(base) period-list(peak) extra-args...
  local net=$1 dir=$2 name=$3 base=$4 peak=$5
  shift 5
  "$PY" "$TOOLS/randomTrips.py" -n "$net" -b 0 -e 3600 -p $base --fringe-factor max \
    --min-distance 400 --seed 42 --validate "$@" --prefix v \
    -o "$work/$name.trips.xml" -r "$dir/$name.rou.xml" >/dev/null
  "$PY" "$TOOLS/randomTrips.py" -n "$net" -b 0 -e 3600 -p $peak --fringe-factor max \
    --min-distance 400 --seed 43 --validate "$@" --prefix p \
    -o "$work/$name.peak.trips.xml" -r "$dir/${name}_peak.rou.xml" >/dev/null
  rm -f "$dir"/*.rou.alt.xml
  for f in "$dir/$name.rou.xml" "$dir/${name}_peak.rou.xml"; do
    strip_route_file "$f"
  done
}

# --- grid4x4 ---------------------------------------------------------------------------------
dir=sumo_data/grid4x4
mkdir -p "$dir"
netgenerate --grid --grid.number 4 --grid.length 200 --grid.attach-length 200 \
  --default.lanenumber 2 --turn-lanes 1 --turn-lanes.length 60 --default.speed 13.89 \
  -j traffic_light --tls.default-type static --tls.layout opposites --no-turnarounds true \
  --seed 42 -o "$dir/grid4x4.net.xml" 2>&1 | grep -v "does not control any links\|Could not build program" || true
# 1.2 s between departures = 3000 vehicles/h; the peak: 3000 -> 6500 -> 3000 vehicles/h in 12-minute steps.
make_demand "$dir/grid4x4.net.xml" "$dir" grid4x4 "1.2" "1.2 0.8 0.55 0.8 1.2"

# --- arterial4x4 -----------------------------------------------------------------------------
dir=sumo_data/arterial4x4
mkdir -p "$dir"
"$PY" - "$work" <<'PY'
import sys
out = sys.argv[1]
dx, dy, n = 250.0, 200.0, 4
nodes, edges = [], []
def node(i, x, y, kind):
    nodes.append(f'    <node id="{i}" x="{x:.1f}" y="{y:.1f}" type="{kind}"/>')
def road(a, b, kind):
    edges.append(f'    <edge id="{a}_{b}" from="{a}" to="{b}" type="{kind}"/>')
for c in range(n):
    for r in range(n):
        node(f"j{c}{r}", c * dx, r * dy, "traffic_light")
for r in range(n):  # east-west arterials with their fringe ends
    node(f"w{r}", -dx, r * dy, "priority"); node(f"e{r}", n * dx, r * dy, "priority")
    chain = [f"w{r}"] + [f"j{c}{r}" for c in range(n)] + [f"e{r}"]
    for a, b in zip(chain, chain[1:]):
        road(a, b, "arterial"); road(b, a, "arterial")
for c in range(n):  # north-south streets
    node(f"s{c}", c * dx, -dy, "priority"); node(f"n{c}", c * dx, n * dy, "priority")
    chain = [f"s{c}"] + [f"j{c}{r}" for r in range(n)] + [f"n{c}"]
    for a, b in zip(chain, chain[1:]):
        road(a, b, "street"); road(b, a, "street")
open(f"{out}/a.nod.xml", "w").write("<nodes>\n" + "\n".join(nodes) + "\n</nodes>\n")
open(f"{out}/a.edg.xml", "w").write("<edges>\n" + "\n".join(edges) + "\n</edges>\n")
open(f"{out}/a.typ.xml", "w").write(
    '<types>\n    <type id="arterial" numLanes="3" speed="16.67" priority="3"/>\n'
    '    <type id="street" numLanes="1" speed="11.11" priority="1"/>\n</types>\n')
PY
netconvert -n "$work/a.nod.xml" -e "$work/a.edg.xml" -t "$work/a.typ.xml" \
  --tls.default-type static --tls.layout opposites \
  --no-turnarounds true -o "$dir/arterial4x4.net.xml" >/dev/null
# Weighted by lanes: the arterials carry most trips; 2400 vehicles/h, peak 2400 -> 5100 -> 2400.
make_demand "$dir/arterial4x4.net.xml" "$dir" arterial4x4 "1.5" "1.5 1.0 0.7 1.0 1.5" --lanes

# One morning hour, 07:00-08:00, its demand peaking in the middle (the periods are randomTrips'
# seconds between departures in five equal parts of the hour).
make_morning_demand() {  # net dir name seed periods...
  local net=$1 dir=$2 name=$3 seed=$4
  shift 4
  "$PY" "$TOOLS/randomTrips.py" -n "$net" -b 25200 -e 28800 -p "$@" --fringe-factor 10 \
    --min-distance 400 --seed "$seed" --validate --prefix v \
    -o "$work/$name.trips.xml" -r "$dir/$name.rou.xml" >/dev/null
  rm -f "$dir"/*.rou.alt.xml
  strip_route_file "$dir/$name.rou.xml"
}

# --- random25 --------------------------------------------------------------------------------
dir=sumo_data/random25
mkdir -p "$dir"
netgenerate --rand --rand.iterations 45 --rand.min-distance 120 --rand.max-distance 300 \
  --rand.connectivity 0.9 --rand.neighbor-dist1 0 --rand.neighbor-dist2 0 \
  --rand.neighbor-dist3 10 --rand.neighbor-dist4 10 --rand.neighbor-dist5 2 --rand.neighbor-dist6 1 \
  --default.lanenumber 2 --default.speed 13.89 --tls.guess true --tls.guess.threshold 30 \
  --junctions.join true --no-turnarounds true --seed 7 -o "$dir/random25.net.xml" >/dev/null 2>&1
make_morning_demand "$dir/random25.net.xml" "$dir" random25 44 1.6 1.1 0.8 1.1 1.6

# --- spider15 --------------------------------------------------------------------------------
dir=sumo_data/spider15
mkdir -p "$dir"
netgenerate --spider --spider.arm-number 5 --spider.circle-number 3 --spider.space-radius 150 \
  --default.lanenumber 2 --default.speed 13.89 -j traffic_light --tls.default-type static \
  --no-turnarounds true --seed 7 -o "$dir/spider15.net.xml" >/dev/null 2>&1
make_morning_demand "$dir/spider15.net.xml" "$dir" spider15 45 2.0 1.4 1.0 1.4 2.0

echo "made: $(ls sumo_data/grid4x4 sumo_data/arterial4x4 sumo_data/random25 sumo_data/spider15 | tr '\n' ' ')"
