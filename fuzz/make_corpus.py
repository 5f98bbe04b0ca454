#!/usr/bin/env python3
"""Writes the seed corpus fuzz/corpus/<target>/: tiny valid files of every format and a few slightly broken ones.

Run it again after a format change (python3 fuzz/make_corpus.py). The .vdb seeds are not made here (writing VDB
needs OpenVDB's C++ library): they were written once with openvdb::io::File (see fuzz/README.md).
"""
import base64
import gzip
import json
import os
import struct
import zlib

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "corpus")
DIMS = (4, 3, 2)
VOXELS = DIMS[0] * DIMS[1] * DIMS[2]


def put(target, name, data):
    folder = os.path.join(ROOT, target)
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, name), "wb") as f:
        f.write(data.encode() if isinstance(data, str) else data)


def gz(data):
    return gzip.compress(data, mtime=0)


UINT8 = bytes(range(VOXELS))
INT16 = struct.pack("<%dh" % VOXELS, *[(i * 37) - 300 for i in range(VOXELS)])
UINT16 = struct.pack("<%dH" % VOXELS, *[i * 1000 for i in range(VOXELS)])
FLOAT32 = struct.pack("<%df" % VOXELS, *[i * 0.25 - 1 for i in range(VOXELS)])


def raw():
    # fuzz_raw: first line = file name (dims and type), the rest = the file.
    put("raw", "uint8", b"vol_4x3x2_uint8.raw\n" + UINT8)
    put("raw", "int16", b"ct_4x3x2_int16.raw\n" + INT16)
    put("raw", "uint16_gz", b"mr_4x3x2_uint16.raw.gz\n" + gz(UINT16))
    put("raw", "float32", b"sim.4x3x2_float32.raw\n" + FLOAT32)
    put("raw", "nan_float32", b"nan_1x1x2_float32.raw\n" + struct.pack("<2f", 1.0, float("nan")))
    put("raw", "short_file", b"vol_4x4x4_uint8.raw\n" + UINT8)
    put("raw", "truncated_gz", b"vol_4x3x2_uint8.raw.gz\n" + gz(UINT8)[:-9])
    put("raw", "no_type", b"vol_4x3x2.raw\n" + UINT8)
    put("raw", "zero_dim", b"vol_0x3x2_uint8.raw\n")
    put("raw", "huge_dims", b"vol_99999999999x99999x2_uint8.raw\n" + UINT8)


def nrrd_header(type_, encoding, endian="little", extra=""):
    # 10 samples along x: VTK reads a first axis of 9 or fewer as vector components.
    return ("NRRD0004\n# tiny\ntype: %s\ndimension: 3\nsizes: 10 3 2\nspacings: 1 0.5 2\nencoding: %s\n"
            "endian: %s\n%s\n" % (type_, encoding, endian, extra))


def nrrd():
    n = 60
    put("nrrd", "uint8_raw", nrrd_header("uint8", "raw").encode() + bytes(range(n)))
    put("nrrd", "int16_big", nrrd_header("short", "raw", "big").encode() + struct.pack(">%dh" % n, *range(-9, n - 9)))
    put("nrrd", "float_gzip", nrrd_header("float", "gzip").encode() + gz(struct.pack("<%df" % n, *range(n))))
    put("nrrd", "ascii", nrrd_header("ushort", "ascii") + " ".join(str(i * 999) for i in range(n)) + "\n")
    put("nrrd", "origin", nrrd_header("uint8", "raw", extra="space: left-posterior-superior\n"
                                      "space directions: (1,0,0) (0,1,0) (0,0,1)\nspace origin: (10,20,30)\n")
        .replace("spacings: 1 0.5 2\n", "").encode() + bytes(range(n)))
    put("nrrd", "short_data", nrrd_header("uint8", "raw").encode() + UINT8[:7])
    put("nrrd", "vector_axis", nrrd_header("uint8", "raw").replace("sizes: 10", "sizes: 4").encode() + UINT8)


def metaimage_header(element, extra=""):
    return ("ObjectType = Image\nNDims = 3\nDimSize = 4 3 2\nElementType = %s\nElementSpacing = 1 1 1.5\n"
            "Offset = 0 0 0\nElementByteOrderMSB = False\n%sElementDataFile = LOCAL\n" % (element, extra))


def metaimage():
    put("metaimage", "uchar", metaimage_header("MET_UCHAR").encode() + UINT8)
    put("metaimage", "short", metaimage_header("MET_SHORT").encode() + INT16)
    put("metaimage", "float", metaimage_header("MET_FLOAT").encode() + FLOAT32)
    packed = zlib.compress(UINT16)
    put("metaimage", "ushort_compressed",
        metaimage_header("MET_USHORT", "CompressedData = True\nCompressedDataSize = %d\n" % len(packed)).encode()
        + packed)
    put("metaimage", "short_data", metaimage_header("MET_UCHAR").encode() + UINT8[:5])


def nifti1(datatype, bitpix, data, slope=1.0, inter=0.0):
    h = bytearray(348)
    struct.pack_into("<i", h, 0, 348)
    struct.pack_into("<8h", h, 40, 3, *DIMS, 1, 1, 1, 1)
    struct.pack_into("<hh", h, 70, datatype, bitpix)
    struct.pack_into("<8f", h, 76, 1, 1.0, 0.5, 2.0, 1, 1, 1, 1)
    struct.pack_into("<fff", h, 108, 352.0, slope, inter)
    struct.pack_into("<hh", h, 252, 1, 0)  # qform_code 1: scanner frame from the quaternion
    struct.pack_into("<6f", h, 256, 0, 0, 0, 5.0, -3.0, 1.0)
    h[344:348] = b"n+1\0"
    return bytes(h) + b"\0\0\0\0" + data


def nifti():
    for target, wrap in (("nifti", lambda d: d), ("nifti_gz", gz)):
        put(target, "uint8", wrap(nifti1(2, 8, UINT8)))
        put(target, "int16_scaled", wrap(nifti1(4, 16, INT16, slope=0.5, inter=10)))
        put(target, "float32", wrap(nifti1(16, 32, FLOAT32)))
        put(target, "short_data", wrap(nifti1(2, 8, UINT8[:10])))
    put("nifti_gz", "truncated_gzip", gz(nifti1(2, 8, UINT8))[:-20])


def vtk_header(mode):
    return ("# vtk DataFile Version 3.0\ntiny\n%s\nDATASET STRUCTURED_POINTS\nDIMENSIONS 4 3 2\n"
            "SPACING 1 1 2\nORIGIN 0 0 0\nPOINT_DATA 24\n" % mode)


def vtk_legacy():
    put("vtk_legacy", "ascii", vtk_header("ASCII") + "SCALARS s unsigned_char 1\nLOOKUP_TABLE default\n"
        + " ".join(str(i) for i in range(VOXELS)) + "\n")
    put("vtk_legacy", "binary_short", vtk_header("BINARY").encode() + b"SCALARS s short 1\nLOOKUP_TABLE default\n"
        + struct.pack(">%dh" % VOXELS, *range(VOXELS)) + b"\n")
    put("vtk_legacy", "binary_float", vtk_header("BINARY").encode() + b"SCALARS s float\nLOOKUP_TABLE default\n"
        + struct.pack(">%df" % VOXELS, *[i * 0.5 for i in range(VOXELS)]) + b"\n")
    put("vtk_legacy", "short_data", vtk_header("ASCII") + "SCALARS s unsigned_char 1\nLOOKUP_TABLE default\n1 2 3\n")
    put("vtk_legacy", "vectors", vtk_header("ASCII") + "VECTORS v float\n" + " ".join("1" for _ in range(3 * VOXELS)))


def vti_file(array, appended=b""):
    return (b'<?xml version="1.0"?>\n<VTKFile type="ImageData" version="0.1" byte_order="LittleEndian" '
            b'header_type="UInt32">\n <ImageData WholeExtent="0 3 0 2 0 1" Origin="0 0 0" Spacing="1 1 2">\n'
            b'  <Piece Extent="0 3 0 2 0 1">\n   <PointData Scalars="s">\n    ' + array +
            b'\n   </PointData>\n   <CellData/>\n  </Piece>\n </ImageData>\n' + appended + b'</VTKFile>\n')


def vti():
    ascii_ = " ".join(str(i) for i in range(VOXELS)).encode()
    put("vti", "ascii", vti_file(b'<DataArray type="UInt8" Name="s" format="ascii">' + ascii_ + b'</DataArray>'))
    inline = base64.b64encode(struct.pack("<I", len(INT16)) + INT16)
    put("vti", "binary_int16", vti_file(b'<DataArray type="Int16" Name="s" format="binary">' + inline +
                                        b'</DataArray>'))
    put("vti", "appended_float", vti_file(b'<DataArray type="Float32" Name="s" format="appended" offset="0"/>',
                                          b' <AppendedData encoding="raw">\n  _' +
                                          struct.pack("<I", len(FLOAT32)) + FLOAT32 + b'\n </AppendedData>\n'))
    put("vti", "short_data", vti_file(b'<DataArray type="UInt8" Name="s" format="ascii">1 2 3</DataArray>'))


def dicom_element(group, element, vr, value):
    if isinstance(value, str):
        value = value.encode()
        value += (b"\0" if vr == b"UI" else b" ") * (len(value) % 2)
    if vr in (b"OB", b"OW", b"OF", b"SQ", b"UT", b"UN"):
        return struct.pack("<HH2sHI", group, element, vr, 0, len(value)) + value
    return struct.pack("<HH2sH", group, element, vr, len(value)) + value


def dicom_slice(z, number, pixels):
    us = lambda v: struct.pack("<H", v)
    meta = b"".join([
        dicom_element(0x0002, 0x0001, b"OB", b"\0\1"),
        dicom_element(0x0002, 0x0002, b"UI", "1.2.840.10008.5.1.4.1.1.4"),
        dicom_element(0x0002, 0x0003, b"UI", "1.2.3.4.%d" % number),
        dicom_element(0x0002, 0x0010, b"UI", "1.2.840.10008.1.2.1"),
    ])
    data = b"".join([
        dicom_element(0x0008, 0x0016, b"UI", "1.2.840.10008.5.1.4.1.1.4"),
        dicom_element(0x0008, 0x0060, b"CS", "MR"),
        dicom_element(0x0018, 0x0050, b"DS", "2"),
        dicom_element(0x0020, 0x000D, b"UI", "1.2.3.4.100"),
        dicom_element(0x0020, 0x000E, b"UI", "1.2.3.4.101"),
        dicom_element(0x0020, 0x0011, b"IS", "1"),
        dicom_element(0x0020, 0x0013, b"IS", str(number)),
        dicom_element(0x0020, 0x0032, b"DS", "0\\0\\%g" % z),
        dicom_element(0x0020, 0x0037, b"DS", "1\\0\\0\\0\\1\\0"),
        dicom_element(0x0020, 0x1041, b"DS", "%g" % z),
        dicom_element(0x0028, 0x0002, b"US", us(1)),
        dicom_element(0x0028, 0x0004, b"CS", "MONOCHROME2"),
        dicom_element(0x0028, 0x0010, b"US", us(3)),  # rows
        dicom_element(0x0028, 0x0011, b"US", us(4)),  # columns
        dicom_element(0x0028, 0x0030, b"DS", "0.5\\0.5"),
        dicom_element(0x0028, 0x0100, b"US", us(16)),
        dicom_element(0x0028, 0x0101, b"US", us(16)),
        dicom_element(0x0028, 0x0102, b"US", us(15)),
        dicom_element(0x0028, 0x0103, b"US", us(1)),
        dicom_element(0x0028, 0x1052, b"DS", "0"),
        dicom_element(0x0028, 0x1053, b"DS", "1"),
        dicom_element(0x7FE0, 0x0010, b"OW", pixels),
    ])
    return (b"\0" * 128 + b"DICM" + dicom_element(0x0002, 0x0000, b"UL", struct.pack("<I", len(meta))) + meta
            + data)


def dicom():
    # fuzz_dicom: slices separated by "\n--SLICE--\n".
    sep = b"\n--SLICE--\n"
    put("dicom", "one_slice", dicom_slice(0, 1, INT16[:24]))
    put("dicom", "two_slices", dicom_slice(0, 1, INT16[:24]) + sep + dicom_slice(2, 2, INT16[24:]))
    put("dicom", "three_slices_unsorted", sep.join(dicom_slice(z, n, INT16[:24]) for n, z in ((1, 4), (2, 0), (3, 2))))
    put("dicom", "short_pixels", dicom_slice(0, 1, INT16[:10]))


def transfer_function():
    preset = {"Name": "tiny", "ColorSpace": "RGB",
              "Points": [0, 0, 0.5, 0, 100, 0.2, 0.5, 0, 200, 1, 0.3, 0.8],
              "RGBPoints": [0, 0, 0, 0, 100, 1, 0.5, 0, 200, 1, 1, 1]}
    put("transfer_function", "object", json.dumps(preset))
    put("transfer_function", "list", json.dumps([preset, {"Points": [0, 1, 0.5, 0]}]))
    for space in ("HSV", "Lab", "Lab/CIEDE2000", "Diverging", "Step"):
        put("transfer_function", space.replace("/", "_"), json.dumps(dict(preset, ColorSpace=space)))
    put("transfer_function", "units", json.dumps([dict(preset, Units="HU", Description="a preset's own words")]))
    put("transfer_function", "opacity_only", '{"Points": [-1000, 0, 0.5, 0, 3000, 1, 0.5, 1]}')
    put("transfer_function", "unsorted", '{"Points": [5, 0, 0.5, 0, 1, 1, 0.5, 0]}')
    put("transfer_function", "not_multiple_of_4", '{"Points": [0, 0, 0.5]}')
    put("transfer_function", "malformed", '[{"Points": [0, 0, 0.5, 0}')


SCALAR_FORMATS = {"uint8": "B", "int16": "h", "uint16": "H", "float32": "f"}


def scalar_values(scalar_type):
    return {"uint8": lambda i: i % 256, "int16": lambda i: i * 37 - 300, "uint16": lambda i: i * 1000 % 65536,
            "float32": lambda i: i * 0.25 - 1}[scalar_type]


def chunk_blob(name, components, size, voxels, scalar_type, entries):
    if name == "labels":
        return struct.pack("<%dI" % voxels, *[i % 2 for i in range(voxels)])
    if name == "scalars":
        value = scalar_values(scalar_type)
        return struct.pack("<%d%s" % (voxels, SCALAR_FORMATS[scalar_type]), *[value(i) for i in range(voxels)])
    if name == "table":  # r, g, b, sigma per entry
        return struct.pack("<%df" % (4 * entries), *[x for e in range(entries)
                                                     for x in (e / entries, 0.5, 1 - e / entries, e * 0.5)])
    return bytes((i * 7 + len(name)) % 251 for i in range(voxels * components * size))


def zstd_frame(data):
    """One zstd frame (RFC 8878) holding `data` uncompressed: an RLE block when every byte is the same, else raw blocks.
    The frame states its size (single segment, 4-byte content size), as the prepared file's frames must."""
    frame = struct.pack("<IBI", 0xFD2FB528, 0xA0, len(data))
    if len(set(data)) == 1:
        return frame + struct.pack("<I", 1 | 1 << 1 | len(data) << 3)[:3] + data[:1]
    pieces = [data[i:i + (128 << 10)] for i in range(0, len(data), 128 << 10)]
    for i, piece in enumerate(pieces):
        frame += struct.pack("<I", (i == len(pieces) - 1) | 0 << 1 | len(piece) << 3)[:3] + piece
    return frame


def slice_delta(block, slice_bytes):
    """A block of a per-voxel chunk as version 6 stores it: each byte less the byte one slice before it in the block."""
    return bytes(b if i < slice_bytes else (b - block[i - slice_bytes]) % 256 for i, b in enumerate(block))


def prepared_file(dims, chunks, version=6, eacd_code="exact", scalar_type="uint8", entries=4, block_bytes=16,
                  edit_block=None):
    """A prepared file. Version 4 and later: each chunk in zstd frames of block_bytes bytes each (the last one the
    rest), each frame with its CRC-32; version 6: a per-voxel chunk's blocks hold their bytes' differences over z
    slices; version 3 and earlier: the chunks raw, each with its CRC-32. edit_block(name, k, frame) may return
    another frame for block k of chunk `name` (its CRC-32 is the new frame's)."""
    voxels = dims[0] * dims[1] * dims[2]
    table, blobs, offset = [], [], 0
    for name, type_, components, size in chunks:
        blob = chunk_blob(name, components, size, voxels, scalar_type, entries)
        entry = {"name": name, "type": type_, "components": components, "offset": offset, "bytes": len(blob)}
        if version >= 4:
            entry["blocks"] = []
            per_voxel = version >= 6 and name not in ("table", "labelTable")
            for k, at in enumerate(range(0, len(blob), block_bytes)):
                block = blob[at:at + block_bytes]
                frame = zstd_frame(slice_delta(block, len(blob) // voxels * dims[0] * dims[1]) if per_voxel else block)
                if edit_block:
                    frame = edit_block(name, k, frame)
                entry["blocks"].append({"compressedBytes": len(frame), "crc32": zlib.crc32(frame)})
                blobs.append(frame)
                offset += len(frame)
        else:
            entry["crc32"] = zlib.crc32(blob)
            blobs.append(blob)
            offset += len(blob)
        table.append(entry)
    header = {
        "grid": {"dims": list(dims), "spacing": [1.0, 1.0, 2.0], "origin": [0.0, 0.0, 0.0]},
        "referenceStep": 1.0, "regionCount": 2,
        "metadata": {"source": "tiny.raw", "classification": "{}", "opacityThreshold": 0.01,
                     "angleThresholdDeg": 3.0, "useNormals": True, "trilinear": False, "distanceCap": 255,
                     "statistics": {}},
        "chunks": table}
    if version >= 2:  # version 1 stored exact EACD only and had no eacdCode
        header["eacdCode"] = eacd_code
    if version >= 3:  # version 3: the scalars and the tabulated transfer function instead of the classified volume
        header["scalarType"] = scalar_type
        header["flatGradient"] = 1e-6
        header["transferTable"] = {"lo": 0.0, "step": 1.0, "entries": entries}
    if version >= 4:  # version 4: every chunk compressed in blocks
        header["compression"] = {"codec": "zstd", "level": 1, "blockBytes": block_bytes}
    if version >= 6:  # version 6: per-voxel chunks coded over z slices
        header["compression"]["filter"] = "sliceDelta"
    header = json.dumps(header, indent=1).encode()
    return (b"VOLPREP\0" + struct.pack("<IQ", version, len(header)) + header + struct.pack("<I", zlib.crc32(header))
            + b"".join(blobs))


def prepared():
    folder = os.path.join(ROOT, "prepared")
    for name in os.listdir(folder) if os.path.isdir(folder) else []:  # seeds of an earlier version go
        os.remove(os.path.join(folder, name))

    def base(scalar_type="uint8"):
        size = struct.calcsize(SCALAR_FORMATS[scalar_type])
        return [("scalars", scalar_type, 1, size), ("table", "float32", 4, 4), ("labels", "uint32", 1, 4)]

    fields = ([("pc", "uint8", 1, 1)] + [("acd%d" % o, "uint8", 1, 1) for o in range(8)]
              + [("eacd%d" % o, "uint8", 3, 1) for o in range(8)])
    put("prepared", "all_chunks", prepared_file((2, 2, 1), base() + fields))
    put("prepared", "no_fields", prepared_file((3, 1, 2), base()))
    put("prepared", "one_block_per_chunk", prepared_file((3, 2, 2), base() + fields, block_bytes=4 << 20))
    put("prepared", "one_byte_blocks", prepared_file((2, 1, 1), base() + fields[:1], block_bytes=1))
    for scalar_type in ("int16", "uint16", "float32"):
        put("prepared", scalar_type + "_scalars",
            prepared_file((3, 1, 2), base(scalar_type) + fields[:1], scalar_type=scalar_type, entries=3))
    put("prepared", "one_entry_table", prepared_file((2, 1, 1), base(), entries=1))
    # Coded EACD (core/extent_code.h): log16 is a uint16 per octant, joint8 a table index byte.
    for code, type_, size in (("log16", "uint16", 2), ("joint8", "uint8", 1)):
        coded = fields[:-8] + [("eacd%d" % o, type_, 1, size) for o in range(8)]
        put("prepared", code + "_chunks", prepared_file((2, 2, 1), base() + coded, eacd_code=code))
    # Version 2 held the classified volume (sigma, colour, normal) instead of the scalars and the table; version 3
    # the chunks uncompressed.
    classified = [("sigma", "float32", 1, 4), ("colour", "float32", 3, 4), ("normal", "float32", 3, 4),
                  ("labels", "uint32", 1, 4)]
    put("prepared", "version_2", prepared_file((2, 2, 1), classified + fields, version=2))
    put("prepared", "version_3", prepared_file((2, 2, 1), base() + fields, version=3))
    put("prepared", "wrong_version", prepared_file((2, 2, 1), base(), version=7))
    put("prepared", "truncated", prepared_file((2, 2, 1), base() + fields)[:-30])
    # Blocks that are not what the chunk table says, each with a matching CRC-32: a frame stating another size, one
    # that is not zstd, one with a byte after it.
    lie = lambda name, k, frame: zstd_frame(b"\1" * 5) if (name, k) == ("labels", 0) else frame
    put("prepared", "frame_of_another_size", prepared_file((2, 2, 1), base(), edit_block=lie))
    junk = lambda name, k, frame: b"not a zstd frame" if (name, k) == ("scalars", 0) else frame
    put("prepared", "not_zstd", prepared_file((2, 2, 1), base(), edit_block=junk))
    extra = lambda name, k, frame: frame + b"\0" if (name, k) == ("table", 1) else frame
    put("prepared", "byte_after_frame", prepared_file((2, 2, 1), base(), edit_block=extra))
    corrupt = bytearray(prepared_file((2, 2, 1), base() + fields))
    corrupt[-5] ^= 0x40  # in eacd7's last frame: its CRC-32 no longer matches
    put("prepared", "block_checksum_mismatch", bytes(corrupt))


if __name__ == "__main__":
    for make in (raw, nrrd, metaimage, nifti, vtk_legacy, vti, dicom, transfer_function, prepared):
        make()
