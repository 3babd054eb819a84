// The operand type pairs of the differential test, generated at compile time (no Python): a
// spread of widths W in 1..128 (1, 2, 7, 8, 16, 31, 32, 33, 53, 63, 64, 65, 96, 127, 128), I from
// below 0 to above W, signed and unsigned, fixed and integer types; and every quantization x
// overflow mode (7 x 5, ap's order; unsigned types take WRAP with N = 1 where WRAP_SM would be)
// on a dozen target shapes, plus the saturation bits N = 1, 2 of WRAP and WRAP_SM. Values are
// random (fixed seed) at run time. The list is shared by every engine (differential.hpp).
#pragma once

#include <utility>

#include "tests/differential/differential.hpp"

namespace voxcast_diff {

template <class... L>
struct join;
template <class... P>
struct join<list<P...>> {
  using type = list<P...>;
};
template <class... P, class... Q, class... R>
struct join<list<P...>, list<Q...>, R...> {
  using type = typename join<list<P..., Q...>, R...>::type;
};

// Every one of the 35 modes (K = 7 Q x 5 O, ap's order) meets three target shapes of the twelve
// below (K, K + 4 and K + 8 modulo 12): each mode on a narrow, a middle and a wide shape in
// turn, each shape under about nine modes. An unsigned target cannot take WRAP_SM (ap: exit(1),
// clone: static_assert): it takes WRAP with one saturation bit there. Each target is paired
// with a source of more fraction bits (quantization on conversion) and, for the signed ones,
// more integer bits (overflow).
template <int W, int I, bool S, class B>
struct shape {
  template <std::size_t K>
  using pair = pr<fx<W, I, S, static_cast<int>(K / 5),
                     (!S && K % 5 == kWRAP_SM) ? int{kWRAP} : static_cast<int>(K % 5),
                     (!S && K % 5 == kWRAP_SM) ? 1 : 0>,
                  B, kModes>;
};
template <std::size_t I, class... Shapes>
struct nth;
template <class First, class... Rest>
struct nth<0, First, Rest...> {
  using type = First;
};
template <std::size_t I, class First, class... Rest>
struct nth<I, First, Rest...> {
  using type = typename nth<I - 1, Rest...>::type;
};
using shape_list_t = list<
    shape<1, 1, true, fx<12, 4, true>>, shape<2, -1, false, fx<10, 3, true>>,
    shape<7, 3, true, fx<16, 6, true>>, shape<8, 8, false, fx<20, 12, true>>,
    shape<31, 10, true, fx<64, 32, true>>, shape<33, 40, true, fx<70, 45, false>>,
    shape<53, 1, true, fx<96, 8, true>>, shape<64, 32, false, fx<100, 50, true>>,
    shape<65, -3, true, fx<127, 0, true>>, shape<96, 96, true, fx<128, 100, true>>,
    shape<127, 63, true, fx<128, 60, false>>, shape<128, 64, true, fx<128, 63, true>>>;
template <std::size_t I, class L>
struct shape_at;
template <std::size_t I, class... S>
struct shape_at<I, list<S...>> {
  using type = typename nth<I, S...>::type;
};
template <std::size_t Offset, std::size_t K>
using rotated = typename shape_at<(K + Offset) % 12, shape_list_t>::type::template pair<K>;
template <std::size_t Offset, std::size_t... K>
list<rotated<Offset, K>...> rotation(std::index_sequence<K...>);
template <std::size_t Offset>
using modes = decltype(rotation<Offset>(std::make_index_sequence<35>{}));

using full_pairs = list<
    // narrow, every signedness combination, I < 0, I > W, W = 1
    pr<fx<8, 4, true>, fx<8, 4, true>>, pr<fx<8, 4, true>, fx<6, 2, false>>,
    pr<fx<6, 2, false>, fx<8, 4, true>>, pr<fx<7, 3, false>, fx<8, 8, false>>,
    pr<fx<1, 1, true>, fx<2, -1, false>>, pr<fx<2, 0, false>, fx<1, -2, true>>,
    pr<fx<7, 9, true>, fx<5, -3, true>>, pr<fx<16, 8, true>, in<12, true>>,
    pr<in<20, false>, fx<24, -4, true>>,
    // around 32 bits (the C-conversion rules of mixed-sign comparisons)
    pr<fx<31, 16, true>, fx<33, 1, false>>, pr<fx<32, 32, true>, fx<32, 32, false>>,
    pr<fx<33, 40, false>, fx<31, -2, true>>,
    // 53 (double), 63, 64, 65
    pr<fx<53, 20, true>, fx<53, 53, false>>, pr<fx<63, 30, true>, fx<64, 64, false>>,
    pr<fx<64, 32, true>, fx<64, 0, true>>, pr<fx<64, 70, true>, fx<64, -10, false>>,
    pr<fx<65, 10, true>, fx<7, 3, false>>,
    // 96, 127, 128 (results limited to 128 bits: the wide operand meets a narrow one)
    pr<fx<96, 48, true>, fx<31, 31, true>>, pr<fx<127, 60, true>, fx<1, 0, false>>,
    pr<fx<128, 64, true>, fx<2, 2, true>>, pr<fx<2, 2, false>, fx<128, 1, true>>,
    pr<fx<128, 128, false>, in<8, false>>,
    // integer types
    pr<in<8, true>, in<8, false>>, pr<in<32, true>, in<32, false>>,
    pr<in<64, false>, in<63, true>>, pr<in<1, true>, in<7, false>>,
    pr<in<127, true>, in<1, false>>, pr<in<16, false>, in<16, false>>>;

using mode_pairs = typename join<
    modes<0>, modes<4>, modes<8>,
    // the saturation bits N of WRAP and WRAP_SM (clone and ap only: ac has no N)
    list<pr<fx<8, 4, true, kTRN, kWRAP, 1>, fx<16, 6, true>, kModes>,
         pr<fx<8, 4, true, kRND, kWRAP, 2>, fx<16, 6, true>, kModes>,
         pr<fx<8, 4, true, kTRN, kWRAP_SM, 1>, fx<16, 6, true>, kModes>,
         pr<fx<8, 4, true, kRND, kWRAP_SM, 2>, fx<16, 6, true>, kModes>,
         pr<fx<8, 4, false, kRND, kWRAP, 2>, fx<16, 6, true>, kModes>,
         pr<fx<70, 30, true, kRND_CONV, kWRAP, 3>, fx<100, 40, true>, kModes>>>::type;

using all_pairs = typename join<full_pairs, mode_pairs>::type;

template <class L>
struct size_of;
template <class... P>
struct size_of<list<P...>> {
  static constexpr int value = static_cast<int>(sizeof...(P));
};
constexpr int pair_count = size_of<all_pairs>::value;

}  // namespace voxcast_diff
