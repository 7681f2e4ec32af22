#!/usr/bin/env python3
"""A loop-closure method written in numpy, evaluated end to end by hoilcd.

The method: every thermal frame shrunk to a 16 x 12 thumbnail, normalised to zero mean and unit
norm; a pair's score is the thumbnails' correlation. hoilcd applies the benchmark's protocol,
labels and metrics to that score matrix, exactly as for its built-in methods.

    PYTHONPATH=build/python python3 examples/python/numpy_method.py DATASET [-o REPORT_DIR]

DATASET is a folder written by `hoilcd render` (or pass --render SCENE to make one first).
"""
import argparse

import numpy as np

import hoilcd


def thumbnails(dataset, width=16, height=12):
    """One zero-mean, unit-norm thumbnail per frame (block means of the 8-bit image)."""
    out = []
    for i in range(len(dataset)):
        image = dataset.thermal(i).astype(np.float64)
        h, w = image.shape
        blocks = image[: h - h % height, : w - w % width].reshape(height, h // height, width, w // width)
        thumb = blocks.mean(axis=(1, 3)).ravel()
        thumb -= thumb.mean()
        out.append(thumb / (np.linalg.norm(thumb) or 1.0))
    return np.array(out)


def score_matrix(dataset):
    """frames x frames scores, higher = more alike; hoilcd picks each query's database out of it."""
    t = thumbnails(dataset)
    return t @ t.T


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("dataset", help="dataset folder (written by hoilcd render)")
    parser.add_argument("--render", metavar="SCENE", help="render SCENE into DATASET first")
    parser.add_argument("--frames", type=int, default=0, help="with --render: only the first N frames")
    parser.add_argument("-o", "--output", metavar="REPORT_DIR",
                        help="also write a report folder, as hoilcd evaluate -o (report.json, queries.csv, report.md)")
    args = parser.parse_args()

    if args.render:
        hoilcd.render(args.render, args.dataset, frames=args.frames)
    dataset = hoilcd.Dataset(args.dataset)
    metrics = hoilcd.evaluate(dataset, score_matrix(dataset), name="numpy_thumb", output=args.output)
    print(f"numpy_thumb on {args.dataset}: MRR {metrics['mrr']:.3f}, R@1 {metrics['recall_at_1']:.3f}, "
          f"R@5 {metrics['recall_at_5']:.3f} over {metrics['queries_scored']} queries")


if __name__ == "__main__":
    main()
