// The frame state as a flat stream of bit patterns, the same on every
// fixed-point mapping (voxcast's clone, Xilinx ap_fixed, Catapult ac_fixed):
// `voxcast synth-script` writes the frame it loaded (clone types) and the
// generated C simulation testbench reads it into the vendor's types
// (hls/tb/vizard2_frame_tb.cpp, docs/synthesis.md). A struct copy could not
// do this: ap_fixed and ac_fixed keep their bits in their own layouts.
//
// visit_frame walks every register and table entry of FrameState in one fixed
// order and hands each scalar to the visitor: v.bits(x) for a fixed-point or
// integer field (its pattern in ceil(W/64) 64-bit chunks, lowest first),
// v.flag(b) for a bool, v.mode(m) for the frame mode. A unit is visited only
// if `present` has it, so a frame loaded for the full design (AllUnits) and
// written with a scene's elaborated units gives exactly the stream a top built
// with those units reads.
//
// Host code for testbenches and tools, never synthesized. C++14.
#pragma once

#include <cstdint>

#include "hls/types.hpp"
#include "hls/units.hpp"
#include "hls/vizard2_top.hpp"

namespace voxcast {
namespace hls {
namespace image {

// The number of 64-bit chunks of a W-bit pattern.
constexpr int chunks(int width) { return (width + 63) / 64; }

// Chunk k of x's pattern (bits [64k + 63, 64k] clipped to the width), and back.
template <class T>
std::uint64_t chunk_of(const T& x, int k) {
  const int lo = 64 * k;
  const int hi = lo + 63 < T::width - 1 ? lo + 63 : T::width - 1;
  return read_bits(x, hi, lo);
}
template <class T>
void set_chunk(T& x, int k, std::uint64_t v) {
  const int lo = 64 * k;
  const int hi = lo + 63 < T::width - 1 ? lo + 63 : T::width - 1;
  write_bits(x, hi, lo, v);
}

template <class T, int N, class V>
void bits_array(T (&a)[N], V& v) {
  for (int i = 0; i < N; ++i) v.bits(a[i]);
}

template <class P, class V>
void visit_unit(GeometryRegisters<P>& g, V& v) {
  v.flag(g.perspective);
  v.flag(g.jitter);
  bits_array(g.A, v);
  bits_array(g.B, v);
  bits_array(g.C, v);
  bits_array(g.O, v);
  bits_array(g.Pcol, v);
  bits_array(g.Rrow, v);
  bits_array(g.U, v);
  bits_array(g.K, v);
  bits_array(g.LO, v);
  bits_array(g.HI, v);
  bits_array(g.dims, v);
  bits_array(g.LAST, v);
  v.bits(g.HX);
  v.bits(g.HXY);
}

template <class P, class V>
void visit_unit(RsqrtRom<P>& rom, V& v) {
  bits_array(rom.seed, v);
}

template <class P, class V>
void visit_entry(ClassEntry<P>& e, V& v) {
  v.bits(e.r);
  v.bits(e.g);
  v.bits(e.b);
  v.bits(e.alpha);
  v.bits(e.ka);
  v.bits(e.kd);
  v.bits(e.ks);
}

template <class P, class V>
void visit_unit(ClassificationTable<P>& t, V& v) {
  for (ClassEntry<P>& e : t.entry) visit_entry(e, v);
}

template <class P, class V>
void visit_unit(PreintegrationTable<P>& t, V& v) {
  v.flag(t.enabled);
  for (ClassEntry<P>& e : t.entry) visit_entry(e, v);
}

template <class P, class V>
void visit_unit(ReflectanceRegisters<P>& r, V& v) {
  bits_array(r.IS, v);
}

template <class P, class V>
void visit_unit(ReflectanceMap<P>& m, V& v) {
  bits_array(m.diffuse, v);
  bits_array(m.specular, v);
}

template <class P, class V>
void visit_unit(CompositorRegisters<P>& c, V& v) {
  v.flag(c.ert_enabled);
  v.bits(c.ert_threshold);
  v.bits(c.RM);
}

template <class P, class V>
void visit_unit(LeapRegisters<P>& l, V& v) {
  v.flag(l.enabled);
  v.bits(l.lb);
  v.bits(l.BX);
  v.bits(l.BXY);
  bits_array(l.prefix, v);
}

template <class P, class V>
void visit_unit(MinMaxMemory<P>& m, V& v) {
  for (MinMaxEntry<P>& e : m.block) {
    v.bits(e.lo);
    v.bits(e.hi);
  }
}

template <class P, class V>
void visit_unit(SegmentOpacityTables<P>& t, V& v) {
  v.flag(t.enabled);
  bits_array(t.tau, v);
  bits_array(t.rom, v);
}

template <class V>
void visit_unit(AbsentUnit&, V&) {}

// Every field of the units `present` has, in one order (see the top of this file).
template <class P, class U, class V>
void visit_frame(FrameState<P, U>& f, Units present, V& v) {
  visit_unit(f.geometry, v);
  if (present.perspective) visit_unit(f.rsqrt, v);
  if (present.classification) visit_unit(f.class_table, v);
  if (present.reflectance_map) {
    visit_unit(f.reflectance_regs, v);
    visit_unit(f.reflectance, v);
  }
  visit_unit(f.compositor, v);
  v.mode(f.mode);
  if (present.space_leaping) {
    visit_unit(f.leap, v);
    visit_unit(f.minmax, v);
  }
  if (present.partial_segments) visit_unit(f.segments, v);
  if (present.preintegration) visit_unit(f.preint, v);
}

}  // namespace image
}  // namespace hls
}  // namespace voxcast
