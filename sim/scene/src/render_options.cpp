#include "hoilcd/sim/scene/render_options.h"

namespace hoilcd {

RenderOptions::RenderOptions() { Table().FillDefaults(this); }

const OptionTable<RenderOptions>& RenderOptions::Table() {
  using O = RenderOptions;
  static const OptionTable<O> table =
      OptionTable<O>()
          .Add("edge_supersampling", &O::edge_supersampling, true,
               "supersample pixels on object, material and depth edges")
          .Add("edge_samples_per_axis", &O::edge_samples_per_axis, 2, "", OptionRange::Closed(1, 8),
               "n x n stratified samples in an edge pixel")
          .Add("specular_reflections", &O::specular_reflections, true, "one traced reflection on specular surfaces")
          .Add("threads", &O::threads, 0, "", OptionRange().AtLeast(0),
               "worker threads (0: the CPUs this process may use)")
          .CodeOnly();
  return table;
}

std::string RenderOptions::Check() const { return Table().FirstProblem(*this); }

}  // namespace hoilcd
