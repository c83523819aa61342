#!/usr/bin/env bash
# Renders the README's pictures and animations into docs/images/ from the built pba (headless:
# EGL, no display needed). Usage: scripts/readme-images.sh [BUILD_DIR] (default build).
set -euo pipefail
cd "$(dirname "$0")/.."
pba=${1:-build}/pba
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# pba replaces only files it wrote itself (the folder's .pba-output lists them), and git's
# checkout wrote these: render into the scratch folder, then copy over the pictures in git.
out=$work/images
mkdir "$out"

still() { # SCENE TIME [SIZE]
  "$pba" render "$1" --size "${3:-640x360}" --time "$2" --out "$out/$1.png"
}
still integrators 6 640x480 # taller, from its own camera: the legend leaves the bounces in view
still bouncing-cube 3
still spring 2
still blow-dryer 6
still cloth-in-the-dryer 4
still blow-dryer-flow 12 640x480 # taller: the legend leaves all five balls in view
# Rigid bodies and what touches them, from each scene's own camera (placed on its action: the
# room's framing shows them small), or from one placed here for the moment shown.
own() { # SCENE TIME [MARKS]
  "$pba" render "$1" --size 640x360 --time "$2" ${3:+--show "$3"} --out "$out/$1.png"
}
rigid() { # SCENE TIME CAMERA [MARKS]
  "$pba" render "$1" --size 640x360 --time "$2" --camera="$3" ${4:+--show "$4"} --out "$out/$1.png"
}
own pyramid 2
own dominoes 1.6 contacts
own newtons-cradle 0.62
own wrecking-ball 1.8
own chain 0.45 joints
own dice 8 # the heap at rest in its tray
own box-stack 2
own incline 0.6
own pendulum 0.4 joints
rigid rolling 0.8 -0.8,1.5,3.8,-1.1,0.2,0 axes
own tennis-racket 4.5 axes
own blow-dryer-boxes 4
own double-pendulum 3.7 joints # the rods bent: the chaos shows
own spring-pendulum 1.3 joints
# Ropes, cloth and the stiff spring, framed the same way.
rigid rope 0.8 0,2.8,6.5,-0.3,1.2,0 # the free end striking the floor
rigid cloth 1.2 0,2.6,5,0,2.2,0
# Particles, ropes and cloth touching rigid bodies.
own cloth-on-box 4
own trampoline 0.56 # the crate deepest in the cloth
own hanging-crate 1.3
rigid cloth-folds 3 0.5,1.0,1.8,0.1,0.0,0
# Balls in the dryer's air: five jostling, and a ping-pong ball up close.
own balls-in-the-dryer 8
rigid ping-pong 10 0.3,0.3,0.75,0,0.12,0
rigid granular 4 0,0.16,0.62,0,0.04,0 # the mound at the end, from low beside it
own stiff-spring 1.5
# The README's first scene, from the example file it shows.
"$pba" render docs/examples/first-scene.json --size 640x360 --time 3 --camera=0,2,6,0,1.6,0 --out "$out/first-scene.png"
"$pba" render blow-dryer-swarm --size 640x360 --time 1.5 --out "$out/blow-dryer-swarm.png"
"$pba" render fountain-1m --size 640x360 --time 1.5 --out "$out/fountain-1m.png"
"$pba" field blow-dryer-flow --slice --out "$out/field-blow-dryer-flow.png"

# The integrator study's height plot (its colours are the viewer's), and the viewer itself with
# its panel, captured at an exact simulated time under a virtual display.
"$pba" compare --out "$work/study" > /dev/null
cp "$work/study/height.png" "$out/compare-height.png"
"$pba" compare stiff-spring --out "$work/stiff" > /dev/null
cp "$work/stiff/stability.png" "$out/stability.png"
"$pba" compare tennis-racket --integrators rk4,implicit-gyroscopic --out "$work/racket" > /dev/null
cp "$work/racket/flip.png" "$out/tennis-racket-flip.png"
xvfb-run -a -s "-screen 0 1280x720x24" "$pba" view integrators --time 1.3 --screenshot "$out/viewer.png"
xvfb-run -a -s "-screen 0 1280x720x24" "$pba" view tennis-racket --time 4.5 --show axes --camera 1.4,2.6,2.2,0,2,0 \
  --screenshot "$out/viewer-tennis-racket.png"

gif() { # SCENE SECONDS SIZE: the first SECONDS at 12 frames a second, a palette of its own
  "$pba" render "$1" --duration "$2" --fps 12 --size "$3" --out "$work/$1.mp4"
  ffmpeg -v error -y -i "$work/$1.mp4" -vf "palettegen=max_colors=96" "$work/$1-palette.png"
  ffmpeg -v error -y -i "$work/$1.mp4" -i "$work/$1-palette.png" -lavfi "paletteuse=dither=bayer" "$out/$1.gif"
}
gif blow-dryer 8 480x270
gif blow-dryer-flow 8 480x360
cp "$out"/* docs/images/
ls -l docs/images
