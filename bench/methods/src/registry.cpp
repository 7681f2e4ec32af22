// The method registry: the built-ins of method_list.h, then whatever RegisterMethod added.
#include <algorithm>

#include "hoilcd/bench/methods/loop_closure_method.h"
#include "hoilcd/bench/methods/methods.h"
#include "hoilcd/core/util/error.h"

namespace hoilcd {

#define HOILCD_METHOD(factory) std::unique_ptr<LoopClosureMethod> factory();
#include "method_list.h"
#undef HOILCD_METHOD

namespace {

struct Registry {
  std::vector<MethodFactory> factories;
  std::vector<std::unique_ptr<LoopClosureMethod>> methods;  // one instance per factory
};

Registry& TheRegistry() {
  static Registry* registry = [] {
    auto* r = new Registry;  // never destroyed: methods may be looked up during static destruction
#define HOILCD_METHOD(factory) r->factories.push_back(&factory);
#include "method_list.h"
#undef HOILCD_METHOD
    for (const MethodFactory& f : r->factories) r->methods.push_back(f());
    return r;
  }();
  return *registry;
}

}  // namespace

void RegisterMethod(const MethodFactory& factory) {
  Registry& r = TheRegistry();
  std::unique_ptr<LoopClosureMethod> method = factory();
  HOILCD_CHECK_MSG(method != nullptr, "a method factory returned no method");
  const std::string name = method->Name();
  HOILCD_CHECK_MSG(std::none_of(r.methods.begin(), r.methods.end(), [&](const auto& m) { return m->Name() == name; }),
                   "a method called " << name << " is registered already");
  HOILCD_CHECK_MSG(name != "all" && name != "paper" && !name.empty() && name.find(',') == std::string::npos,
                   "method name '" << name << "' is reserved or has a comma");
  r.factories.push_back(factory);
  r.methods.push_back(std::move(method));
}

const std::vector<std::unique_ptr<LoopClosureMethod>>& RegisteredMethods() { return TheRegistry().methods; }

const LoopClosureMethod& FindMethod(const std::string& name) {
  for (const auto& m : RegisteredMethods())
    if (m->Name() == name) return *m;
  HOILCD_CHECK_MSG(false, "unknown method " << name);
  std::abort();
}

std::unique_ptr<LoopClosureMethod> CreateMethod(const std::string& name) {
  const Registry& r = TheRegistry();
  for (size_t i = 0; i < r.methods.size(); ++i)
    if (r.methods[i]->Name() == name) return r.factories[i]();
  HOILCD_CHECK_MSG(false, "unknown method " << name);
  std::abort();
}

}  // namespace hoilcd
