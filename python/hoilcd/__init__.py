"""hoilcd: synthetic thermal scene simulator and loop-closure benchmark, from Python.

Dataset(path) reads a dataset folder as numpy arrays; render() writes one from a scene file;
bench() runs the built-in loop-closure methods; evaluate() scores your own method's score
matrix with the benchmark's protocol, labels and metrics. Bad input raises hoilcd.InputError
(a ValueError) with the same message the hoilcd command prints.

Importing it turns OpenCV's own thread pool off for the process (cv2's calls included), so that
render() and bench() use the threads they are given, as the hoilcd command does.
"""
from ._hoilcd import (InputError, Dataset, render, bench, evaluate, methods, data_dir,  # noqa: F401
                      __version__)
