// MOTChallenge export of a dataset, laid out for TrackEval's MOTChallenge 2D box reader: the
// ground-truth person boxes (persons.json) and the DLCD front end's tracks, so TrackEval users can
// score hoilcd's tracker. Benchmark "HOILCD", split "train", one sequence per dataset, named after
// its scene, seed and scene hash, so several datasets exported into one folder sit side by side.
#pragma once

#include <string>
#include <vector>

#include "hoilcd/bench/methods/bench_options.h"
#include "hoilcd/core/dataset/dataset.h"

namespace hoilcd {

// gt.txt: frame,id,left,top,width,height,consider,class,visibility (frames and ids from 1). People
// the tracking metrics do not score (options: too occluded or too small) get consider 0 and class
// 8 (distractor), so TrackEval counts them neither missed nor false positives, as the bench does.
std::string MotGroundTruth(const std::vector<FramePersons>& persons, const TrackingMetricsOptions& options);

// Tracker file: frame,id,left,top,width,height,conf,-1,-1,-1 (frames and ids from 1).
std::string MotTracks(const std::vector<FrameTracks>& tracks);

// "HOILCD-<scene name>-seed<seed>-<first 8 hex digits of the scene hash>", characters other than
// letters, digits and '-' replaced by '_'.
std::string MotSequenceName(const Dataset& dataset);

struct MotExport {
  std::string sequence;      // sequence name
  std::string ground_truth;  // path of gt.txt
  std::string tracks;        // path of the tracker file
};

// Runs the DLCD front end (bench defaults, the dataset's manifest) and writes under out_dir:
// gt/mot_challenge/HOILCD-train/<seq>/{gt/gt.txt,seqinfo.ini}, gt/mot_challenge/seqmaps/HOILCD-train.txt
// (the sequence added to those already listed there) and
// trackers/mot_challenge/HOILCD-train/hoilcd-dlcd/data/<seq>.txt.
MotExport ExportMot(const Dataset& dataset, const BenchOptions& options, const std::string& out_dir);

}  // namespace hoilcd
