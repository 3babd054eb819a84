// no-rtti: typeid, and dynamic_cast (whose polymorphic class is also a
// no-virtual finding).
#include <typeinfo>

#include "hls/pragma.hpp"

namespace {
struct Base {
  virtual ~Base() = default;  // expect-lint: no-virtual
};
struct Derived : Base {};
int kind(const Base& b) {
  const bool same = typeid(b) == typeid(Derived);             // expect-lint: no-rtti
  return same && dynamic_cast<const Derived*>(&b) != nullptr;  // expect-lint: no-rtti
}
}  // namespace

void lint_top(int* out) {
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = out)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE s_axilite port = return)
  const Derived d;
  *out = kind(d);
}
