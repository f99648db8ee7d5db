#pragma once
// The Config of a wrapper that takes no options (ClipAction, DiscreteAsBox,
// OneHotObservation): any key other than `id` in its YAML entry is an error.
namespace rlrun {

struct NoOptions {
  template <class V>
  void visit(V& /*v*/) {}
};

}  // namespace rlrun
