// Concatenation must not compile with the clone (issue 16): ap overloads the comma operator as
// bit concatenation on ap_int_base, range and bit references and C integers next to them, and
// without an overload C++ would take the built-in comma and yield the right operand silently
// ((a.range(7, 0), b.range(7, 0)) was 0xdc where ap gives 0x18dc). hls/fixed_point.hpp deletes
// operator, for exactly those pairs.
//
// The ctest cases fixed_point_concat_refused_<case>_<compiler> compile this file with
// -DVOXCAST_CONCAT_CASE=<case> and pass only when the compiler names the deleted operator,
// (not on any other error); fixed_point_concat_control_<compiler> compiles every case with the
// comma replaced by two plain uses of the operands (-DVOXCAST_CONCAT_CONTROL), so the operands
// themselves are valid code.
#include "hls/fixed_point.hpp"

namespace h = voxcast::hls;

template <class T>
void use(const T&) {}

#ifdef VOXCAST_CONCAT_CONTROL
#define PAIR(l, r) (use(l), use(r))
#else
#define PAIR(l, r) static_cast<void>(((l), (r)))
#endif
#ifndef VOXCAST_CONCAT_CASE
#define VOXCAST_CONCAT_CASE 0  // every case
#endif
#define CASE(n) (VOXCAST_CONCAT_CASE == 0 || VOXCAST_CONCAT_CASE == (n))

void cases() {
  h::fixed<8, 4> a = 1.5;
  h::fixed<8, 4> b = -2.25;
  const h::fixed<8, 4> ca = a;
  h::uint_t<8> x = 0x18;
  h::int_t<4> y = -2;
#if CASE(1)
  PAIR(a.range(7, 0), b.range(7, 0));  // issue 16: ap gives 0x18dc
#endif
#if CASE(2)
  PAIR(x, y);  // ap_uint<8>, ap_int<4>: 12 bits
#endif
#if CASE(3)
  PAIR(x, 5);  // ap_uint<8>, int: 40 bits
#endif
#if CASE(4)
  PAIR(5u, x);  // unsigned, ap_uint<8>
#endif
#if CASE(5)
  PAIR(a[7], b[0]);  // two bit references
#endif
#if CASE(6)
  PAIR(ca.range(3, 0), x.range(7, 4));  // a const fixed's range, an int's range
#endif
#if CASE(7)
  PAIR(x.range(7, 4), true);  // a range and a bool
#endif
  use(a);
  use(b);
  use(ca);
  use(x);
  use(y);
}

int main() {
  cases();
  return 0;
}
