#!/usr/bin/env bash
# Regenerates the pictures of the README, all drawn by ikarus itself:
#   bash docs/regenerate.sh
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet
ikarus=target/release/ikarus

# The seed arm moving to a goal through a via point, eased with Parent's k1/k2 curve.
$ikarus animate --goal -2,3 --via 4,1.5 --ease parent --k1 0.3 --k2 0.7 --frames 40 --fps 20 \
  --width 420 --height 420 --out docs/src/images/motion.gif > /dev/null
# The same motion as one picture: ghost poses fading in, the path of every joint marked.
$ikarus animate --goal -2,3 --via 4,1.5 --ease parent --k1 0.3 --k2 0.7 --frames 24 \
  --width 560 --height 560 --out docs/src/images/motion.png > /dev/null
# The seed arm tracing a figure-8 (plan mode): the dashed path, the tip's trace, the ghost poses.
$ikarus track --figure8 0.5,2.5,3 --samples 80 --width 560 --height 560 --out docs/src/images/track.png > /dev/null
# What the seed's ranges leave of the annulus the free arm reaches: the exact region, seven arcs.
$ikarus workspace --limits --width 560 --height 560 --out docs/src/images/workspace-limits.png > /dev/null
# The puppet reaching with both hands while its feet stay planted (limits on, wedges drawn).
$ikarus solve --rig examples/rigs/puppet.toml --goal right_hand=0.6451,1.0024 --goal left_hand=0.8118,0.5652 \
  --pin left_foot --pin right_foot --limits --width 560 --height 560 --out docs/src/images/puppet.png > /dev/null
# Spineboy walking (0.4 s into walk), its front leg's target moved, posed by ikarus's solver.
$ikarus pose --rig examples/characters/spine-spineboy-pro.json --animation walk --time 0.4 \
  --target front-leg-target=60,60 --ik ikarus --width 420 --height 520 --out docs/src/images/spineboy-ikarus.png 2> /dev/null
# The raptor's front leg as one four-bone limb reaching a foot target the runtime's rules leave short.
$ikarus pose --rig examples/characters/spine-raptor-pro.json --animation walk --time 0.4 \
  --target front-foot-target=520,80 --ik ikarus --ik-file examples/characters/raptor-legs.ik.toml \
  --width 560 --height 460 --out docs/src/images/raptor-ikarus.png 2> /dev/null
# Parent's ease with the errata's corrected formula: position and velocity against time.
$ikarus render ease --k1 0.3 --k2 0.75 --width 560 --height 420 --out docs/src/images/ease.png
# The playground, as the browser test leaves it: FABRIK on a clicked goal, the free area.
bash e2e/run > /dev/null
cp target/e2e/playground.png docs/src/images/playground.png
# The playground as an animation tool: the puppet's walk keyed, played with onion skins, a knee flipped, zoomed.
(cd e2e && node record.mjs > /dev/null)
# Spineboy's art on the page: walk with the bones over it, and a key dragged with onion skins of art.
(cd e2e && ART_DOCS=1 node --test --test-name-pattern="spineboy's art" art.test.mjs > /dev/null)
echo "docs/src/images/: $(ls docs/src/images/*.png docs/src/images/*.gif | tr '\n' ' ')"
