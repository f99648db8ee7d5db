#!/usr/bin/env bash
# Rebuilds sumo_data/single_intersection/single.net.xml from its plain XML sources with SUMO's
# netconvert (committed, so training does not need this step).
set -euo pipefail
cd "$(dirname "$0")/../../sumo_data/single_intersection"
netconvert --node-files nodes.nod.xml --edge-files edges.edg.xml \
  --connection-files connections.con.xml --no-turnarounds true \
  --output-file single.net.xml
