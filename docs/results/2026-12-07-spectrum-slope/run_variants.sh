#!/bin/bash
cd /tmp/slope
for v in "$@"; do
  ./render_variants.sh $v > log_$v.txt 2>&1
  nice -n 10 /usr/bin/python3 extract.py pr_$v pr_$v.npz >> summary_variants.txt 2>&1 && rm -rf pr_$v
done
