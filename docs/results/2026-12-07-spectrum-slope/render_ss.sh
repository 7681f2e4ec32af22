#!/bin/bash
# 4x supersampled render (1024x768, same 50 deg HFOV), every sensor effect off: the ideal image to box-integrate in python.
export HOILCD_DATA_DIR=/work/main
EFF="optics_blur temporal_noise fixed_pattern drift lens_shading ffc_freeze time_constant quantisation"
S=""; for e in $EFF; do S="$S --set camera.$e=false"; done
nice -n 10 /work/main/build/bin/hoilcd -q render /work/main/scenes/paper_room.json -o /tmp/slope/pr_ss4 --outputs radiometric --threads 1 \
  --set camera.width_px=1024 --set camera.height_px=768 $S
