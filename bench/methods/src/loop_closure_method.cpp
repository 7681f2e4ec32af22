#include "hoilcd/bench/methods/loop_closure_method.h"

#include "hoilcd/core/util/error.h"

namespace hoilcd {

const MethodScores& MethodContext::Input(const std::string& name) const {
  const auto it = scored.find(name);
  HOILCD_CHECK_MSG(it != scored.end(), "method " << name << " was not scored before the method that reads it");
  return it->second;
}

std::vector<double> MethodContext::PerQuery(const std::vector<double>& per_frame) const {
  std::vector<double> out;
  for (const Query& q : queries()) out.push_back(per_frame[q.frame]);
  return out;
}

std::vector<MethodScores> LoopClosureMethod::ScoreTogether(const std::vector<const LoopClosureMethod*>& methods,
                                                           const std::vector<MethodContext>& contexts) const {
  HOILCD_CHECK_MSG(methods.size() == 1 && contexts.size() == 1 && methods.front() == this,
                   Name() << " returns a PassKey but does not override ScoreTogether to score its pass");
  return {Score(contexts.front())};
}

}  // namespace hoilcd
