#!/usr/bin/env python3
"""Writes the binary seed corpora of fuzz/corpus/ (docs/extremes.md, "Fuzzing").

The seeds are small (<= a few KB) valid files and typical broken variants of
them; libFuzzer mutates from there. The scene_toml seeds are text files kept in
git directly. Run from the repository root: python3 fuzz/make_corpus.py
"""
import gzip
import os
import struct

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "corpus")


def put(target, name, data):
    d = os.path.join(ROOT, target)
    os.makedirs(d, exist_ok=True)
    with open(os.path.join(d, name), "wb") as f:
        f.write(data)


# --- NIfTI-1 (nifti1.h: 348-byte header, 4-byte extension flag, data at 352) ---
DT = {"u8": (2, 8, "B"), "i16": (4, 16, "h"), "u16": (512, 16, "H"), "f32": (16, 32, "f"),
      "i32": (8, 32, "i"), "f64": (64, 64, "d")}


def nifti_header(dims, dt, pixdim=(1.0, 1.0, 1.0), slope=1.0, inter=0.0, vox_offset=352.0,
                 magic=b"n+1\0", ndim=3):
    code, bitpix, _ = DT[dt]
    h = bytearray(348)
    struct.pack_into("<i", h, 0, 348)
    dim = [ndim] + list(dims) + [1] * (7 - len(dims))
    struct.pack_into("<8h", h, 40, *dim)
    struct.pack_into("<hh", h, 70, code, bitpix)
    struct.pack_into("<8f", h, 76, 1.0, *pixdim, 0.0, 0.0, 0.0, 0.0)
    struct.pack_into("<f", h, 108, vox_offset)
    struct.pack_into("<ff", h, 112, slope, inter)
    struct.pack_into("<B", h, 123, 2)  # xyzt_units: mm
    h[344:348] = magic
    return bytes(h) + b"\0\0\0\0"


def nifti(dims, dt, values, **kw):
    fmt = "<%d%s" % (len(values), DT[dt][2])
    return nifti_header(dims, dt, **kw) + struct.pack(fmt, *values)


ramp = list(range(4 * 3 * 2))
put("nifti", "u8_4x3x2.nii", nifti((4, 3, 2), "u8", ramp))
put("nifti", "i16_4x3x2_slope.nii", nifti((4, 3, 2), "i16", [v - 12 for v in ramp], slope=2.0, inter=-1000.0))
put("nifti", "u16_2x2x2.nii", nifti((2, 2, 2), "u16", [0, 65535, 1, 2, 3, 4, 5, 6]))
put("nifti", "f32_2x2x2.nii", nifti((2, 2, 2), "f32", [0.5, -1.0, 2.0, 3.5, 0.0, 1e3, -7.25, 4.0]))
put("nifti", "f64_1x1x1.nii", nifti((1, 1, 1), "f64", [42.0]))
put("nifti", "i32_aniso.nii", nifti((3, 1, 2), "i32", [0, 1, 2, 3, 4, -7000], pixdim=(0.5, 5.0, 1.0)))
put("nifti", "broken_i32_wider_than_16_bits.nii", nifti((3, 1, 2), "i32", [0, 1, 2, 3, 4, 70000]))
put("nifti", "u8_4x3x2.nii.gz", gzip.compress(nifti((4, 3, 2), "u8", ramp), mtime=0))
put("nifti", "broken_truncated.nii", nifti((4, 3, 2), "u8", ramp)[:360])
put("nifti", "broken_negative_dim.nii", nifti((4, -3, 2), "u8", ramp))
put("nifti", "broken_absurd_dims.nii", nifti((32767, 32767, 32767), "u8", ramp))
put("nifti", "broken_nan_pixdim.nii", nifti((2, 2, 2), "u8", ramp[:8], pixdim=(float("nan"), 1.0, 1.0)))
put("nifti", "broken_vox_offset.nii", nifti((2, 2, 2), "u8", ramp[:8], vox_offset=100.0))
put("nifti", "broken_4d.nii", nifti((2, 2, 2, 3), "u8", ramp, ndim=4))
put("nifti", "broken_header_only.nii", nifti_header((2, 2, 2), "u8")[:200])

# --- raw: 8 bytes of RawSpec (fuzz/targets/volume_loaders.cpp), then the file ---
def raw_spec(dims, type_index, flags):
    return struct.pack("<3hBB", *dims, type_index, flags)


put("raw", "u8_4x3x2", raw_spec((4, 3, 2), 0, 0) + bytes(ramp))
put("raw", "u16_be_2x2x2", raw_spec((2, 2, 2), 1, 1) + struct.pack(">8H", 0, 65535, 1, 2, 3, 4, 5, 6))
put("raw", "i16_le_2x2x2_aniso", raw_spec((2, 2, 2), 2, 0b0001_0100) + struct.pack("<8h", -32768, 32767, -1, 0, 1, 2, 3, 4))
put("raw", "broken_short", raw_spec((4, 4, 4), 1, 0) + bytes(20))
put("raw", "broken_zero_dim", raw_spec((0, 4, 4), 0, 0) + bytes(16))
put("raw", "broken_negative_spacing", raw_spec((2, 2, 2), 0, 0b0010_0000) + bytes(8))
put("raw", "broken_zero_spacing", raw_spec((2, 2, 2), 0, 0b0000_0110) + bytes(8))
put("raw", "one_voxel", raw_spec((1, 1, 1), 0, 0) + b"\xff")

# --- DICOM Part 10, explicit VR little endian, one 4x4 slice -----------------------
def elem(group, element, vr, value):
    if isinstance(value, str):
        value = value.encode()
        if len(value) % 2:
            value += b"\0" if vr == "UI" else b" "
    head = struct.pack("<HH", group, element) + vr.encode()
    if vr in ("OB", "OW", "SQ", "UN", "UT"):
        return head + b"\0\0" + struct.pack("<I", len(value)) + value
    return head + struct.pack("<H", len(value)) + value


def us(v):
    return struct.pack("<H", v)


def dicom(rows=4, cols=4, bits=16, signed=1, pixels=None, position="0\\0\\0", slope="1",
          intercept="-1024", spacing="0.5\\0.5", drop=()):
    ts = "1.2.840.10008.1.2.1"
    meta_body = (elem(0x0002, 0x0001, "OB", b"\0\1") +
                 elem(0x0002, 0x0002, "UI", "1.2.840.10008.5.1.4.1.1.2") +
                 elem(0x0002, 0x0003, "UI", "1.2.3.4.5.6.7") +
                 elem(0x0002, 0x0010, "UI", ts))
    meta = elem(0x0002, 0x0000, "UL", struct.pack("<I", len(meta_body))) + meta_body
    if pixels is None:
        pixels = [(r * cols + c) * 10 for r in range(rows) for c in range(cols)]
    pix = struct.pack("<%d%s" % (len(pixels), "h" if signed else "H"), *pixels) if bits == 16 \
        else bytes(p & 0xff for p in pixels)
    fields = [
        (0x0008, 0x0016, "UI", "1.2.840.10008.5.1.4.1.1.2"),
        (0x0008, 0x0018, "UI", "1.2.3.4.5.6.7"),
        (0x0008, 0x0060, "CS", "CT"),
        (0x0018, 0x0050, "DS", "1"),
        (0x0020, 0x000D, "UI", "1.2.3.4"),
        (0x0020, 0x000E, "UI", "1.2.3.4.5"),
        (0x0020, 0x0013, "IS", "1"),
        (0x0020, 0x0032, "DS", position),
        (0x0020, 0x0037, "DS", "1\\0\\0\\0\\1\\0"),
        (0x0028, 0x0002, "US", us(1)),
        (0x0028, 0x0004, "CS", "MONOCHROME2"),
        (0x0028, 0x0010, "US", us(rows)),
        (0x0028, 0x0011, "US", us(cols)),
        (0x0028, 0x0030, "DS", spacing),
        (0x0028, 0x0100, "US", us(bits)),
        (0x0028, 0x0101, "US", us(bits)),
        (0x0028, 0x0102, "US", us(bits - 1)),
        (0x0028, 0x0103, "US", us(signed)),
        (0x0028, 0x1052, "DS", intercept),
        (0x0028, 0x1053, "DS", slope),
        (0x7FE0, 0x0010, "OW" if bits == 16 else "OB", pix),
    ]
    body = b"".join(elem(*f) for f in fields if (f[0], f[1]) not in drop)
    return b"\0" * 128 + b"DICM" + meta + body


put("dicom", "ct_4x4_i16.dcm", dicom())
put("dicom", "mr_3x5_u8.dcm", dicom(rows=3, cols=5, bits=8, signed=0, intercept="0"))
put("dicom", "ct_1x1.dcm", dicom(rows=1, cols=1, pixels=[-1024]))
put("dicom", "broken_truncated.dcm", dicom()[:-9])
put("dicom", "broken_no_position.dcm", dicom(drop={(0x0020, 0x0032)}))
put("dicom", "broken_zero_slope.dcm", dicom(slope="0"))
put("dicom", "broken_rows_mismatch.dcm", dicom(rows=40, pixels=list(range(16))))
put("dicom", "broken_no_pixels.dcm", dicom(drop={(0x7FE0, 0x0010)}))

# --- fixed_point: op bytes (fuzz/targets/fixed_point.cpp) --------------------------
def conv_double(target, d):
    return bytes([0, target & 0xff, target >> 8, 4]) + struct.pack("<d", d)


def conv_source(target, src, raw):
    return bytes([0, target & 0xff, target >> 8, src]) + struct.pack("<Q", raw)


def arith(a, b, ra, rb):
    return bytes([1, a, b]) + struct.pack("<QQ", ra, rb)


def bittrue(x, which, ra=0, rb=0):
    return bytes([2]) + struct.pack("<d", x) + bytes([which]) + struct.pack("<QQ", ra, rb)


specials = [0.0, -0.0, 1.25, -1.25, 0.75, -0.75, 1.96875, 19.0, -19.0, 8.0, -9.0,
            float("inf"), float("-inf"), float("nan"), -float("nan"), 5e-324, -5e-324,
            1.7976931348623157e308, -1.7976931348623157e308, 2.0 ** 63, -(2.0 ** 63)]
put("fixed_point", "doubles", b"".join(conv_double(t * 37, d) for t, d in enumerate(specials)))
put("fixed_point", "sources", b"".join(conv_source(t * 53, t % 4, r) for t, r in enumerate(
    [0, 1, 0x8000000000000000, 0x7fffffffffffffff, 0xffffffffffffffff, 0x80, 0x8000000000])))
put("fixed_point", "arith", b"".join(arith(a, b, 0x8000000080008080, 0xffffffff7fff7f7f)
                                     for a in range(6) for b in range(6)))
put("fixed_point", "bittrue", b"".join(bittrue(x, w, 0x8000, 0xfff) for w in range(4)
                                       for x in [0.5, -0.5, 0.1, -3.75, 1e9, 0.99999]))
