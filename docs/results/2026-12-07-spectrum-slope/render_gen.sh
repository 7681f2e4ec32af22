#!/bin/bash
cd /tmp/slope
while pgrep -f "render_ss.sh" > /dev/null; do sleep 10; done
export HOILCD_DATA_DIR=/work/main
for d in oo mr; do
  s=$(ls gen_$d/*.json | head -1)
  nice -n 10 /work/main/build/bin/hoilcd -q render $s -o /tmp/slope/${d}_full --frames 1500 --outputs radiometric,exr --threads 1 > log_$d.txt 2>&1
  nice -n 10 /usr/bin/python3 extract.py ${d}_full ${d}_full.npz --keep >> summary_gen.txt 2>&1 && rm -rf ${d}_full/exr
done
