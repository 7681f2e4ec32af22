// report.html's gallery of queries (the sample of gallery_sample.h): each sampled query beside its
// true match and every method's top-1, as inline SVG over the frames (each frame embedded once as a
// JPEG data URI), with the features a method matches, its matches and its RANSAC inliers drawn
// where the method gives them (LoopClosureMethod::MatchPair, re-run for the sampled pairs only),
// and the query's conditions; filterable by method, stratum and outcome.
#pragma once

#include <string>
#include <vector>

#include "hoilcd/bench/evaluation/protocol.h"
#include "hoilcd/bench/evaluation/query_conditions.h"
#include "hoilcd/bench/report/gallery_sample.h"
#include "hoilcd/bench/runner/runner.h"
#include "hoilcd/core/dataset/dataset.h"

namespace hoilcd {

// One method as the gallery shows it.
struct GalleryMethod {
  std::string name;                         // a registered method's name draws its features and matches
  const std::vector<QueryRecord>* records;  // per query
};

struct GalleryInput {
  const Dataset& dataset;
  const std::vector<Query>& queries;
  const std::vector<QueryConditions>& conditions;  // parallel to queries
  std::vector<std::string> stratifications;        // the report's (StratificationsOf its strata)
  std::vector<GalleryMethod> methods;              // in report order
  const std::vector<FrameFeatures>* features;      // per frame (BenchResult::features); null: none
  std::vector<std::string> params;                 // the run's --param values (the methods' own options)
  GallerySampling sampling;                        // SampleGallery's
};

struct Gallery {
  std::vector<size_t> sampled;  // query indices, ascending (SampleGallery)
  std::string html;             // the section: heading, filters, legend, frames, one .entry per query
};

Gallery MakeGallery(const GalleryInput& input);

}  // namespace hoilcd
