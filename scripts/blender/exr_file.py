"""OpenEXR scanline files in pure Python (the Blenders phongcl is checked with do not all ship numpy, and
the host's Python has no EXR module): write() an uncompressed 32-bit float RGB image, read() the float
or half channels of an uncompressed or ZIP-compressed one (what Cycles' multilayer EXRs are).
Images are lists of rows, top row first (EXR's order), each row a list of pixels.
"""
import struct
import zlib

MAGIC = 20000630
NO_COMPRESSION, ZIPS_COMPRESSION, ZIP_COMPRESSION = 0, 2, 3
LINES_PER_BLOCK = {NO_COMPRESSION: 1, ZIPS_COMPRESSION: 1, ZIP_COMPRESSION: 16}
HALF, FLOAT = 1, 2
TILED, DEEP, MULTIPART = 0x200, 0x800, 0x1000  # version field flags (0x400, long names, is read)


def _attribute(name, kind, value):
    return name.encode() + b"\0" + kind.encode() + b"\0" + struct.pack("<i", len(value)) + value


def write(path, rows):
    """rows: height lists of width (r, g, b) floats, top row first."""
    height, width = len(rows), len(rows[0])
    write_lines(path, width, height,
                lambda y: b"".join(struct.pack("<%df" % width, *(pixel[c] for pixel in rows[y])) for c in (2, 1, 0)))


def write_lines(path, width, height, line):
    """line(y): row y's B, G and R floats packed ("<f", width each), top row first; one row in memory
    at a time, for maps larger than a list of rows can hold."""
    channels = b"".join(name + b"\0" + struct.pack("<iB3xii", FLOAT, 0, 1, 1) for name in (b"B", b"G", b"R")) + b"\0"
    window = struct.pack("<iiii", 0, 0, width - 1, height - 1)
    header = (struct.pack("<ii", MAGIC, 2) + _attribute("channels", "chlist", channels)
              + _attribute("compression", "compression", bytes([NO_COMPRESSION]))
              + _attribute("dataWindow", "box2i", window) + _attribute("displayWindow", "box2i", window)
              + _attribute("lineOrder", "lineOrder", b"\0") + _attribute("pixelAspectRatio", "float", struct.pack("<f", 1.0))
              + _attribute("screenWindowCenter", "v2f", struct.pack("<ff", 0.0, 0.0))
              + _attribute("screenWindowWidth", "float", struct.pack("<f", 1.0)) + b"\0")
    line_size = 8 + 3 * 4 * width
    first = len(header) + 8 * height
    with open(path, "wb") as out:
        out.write(header + struct.pack("<%dQ" % height, *(first + y * line_size for y in range(height))))
        for y in range(height):
            data = line(y)
            assert len(data) == line_size - 8, "row %d: %d bytes, expected %d" % (y, len(data), line_size - 8)
            out.write(struct.pack("<ii", y, len(data)) + data)


def _headers(data):
    """Each part's header attributes (one part unless the file is multi-part, as Blender 5's multilayer
    EXRs are), and where the offset tables begin."""
    if struct.unpack_from("<i", data)[0] != MAGIC:
        raise ValueError("not an OpenEXR file")
    flags = struct.unpack_from("<i", data, 4)[0]
    if flags & (TILED | DEEP):
        raise ValueError("tiled or deep EXR: only scanline files are read")
    headers, at = [], 8
    while True:
        attributes = {}
        while data[at] != 0:
            name_end = data.index(b"\0", at)
            kind_end = data.index(b"\0", name_end + 1)
            size = struct.unpack_from("<i", data, kind_end + 1)[0]
            attributes[data[at:name_end].decode()] = data[kind_end + 5:kind_end + 5 + size]
            at = kind_end + 5 + size
        headers.append(attributes)
        at += 1
        if not flags & MULTIPART:
            return headers, at
        if data[at] == 0:  # an empty header ends a multi-part file's headers
            return headers, at + 1


def _channels(chlist):
    channels, at = [], 0
    while chlist[at] != 0:
        end = chlist.index(b"\0", at)
        channels.append((chlist[at:end].decode(), struct.unpack_from("<i", chlist, end + 1)[0]))
        at = end + 17
    return channels


def _unzip(block):
    """ZIP blocks: zlib, then a byte predictor, then the two halves interleaved (OpenEXR's ImfZip.cpp)."""
    raw = bytearray(zlib.decompress(block))
    for i in range(1, len(raw)):
        raw[i] = (raw[i - 1] + raw[i] - 128) & 0xFF
    half = (len(raw) + 1) // 2
    out = bytearray(len(raw))
    out[0::2], out[1::2] = raw[:half], raw[half:]
    return bytes(out)


def _read_part(data, attributes, offsets, multipart, names, images):
    compression = attributes["compression"][0]
    if compression not in LINES_PER_BLOCK:
        raise ValueError("EXR compression %d is not read (uncompressed, ZIPS and ZIP are)" % compression)
    xmin, ymin, xmax, ymax = struct.unpack("<iiii", attributes["dataWindow"])
    width = xmax - xmin + 1
    channels = sorted(_channels(attributes["channels"]))
    lines = LINES_PER_BLOCK[compression]
    for offset in offsets:
        offset += 4 if multipart else 0  # a multi-part chunk starts with its part's number
        y, size = struct.unpack_from("<ii", data, offset)
        block = data[offset + 8:offset + 8 + size]
        rows = min(lines, ymax - y + 1)
        if compression != NO_COMPRESSION and size < rows * width * sum(2 if t == HALF else 4 for _, t in channels):
            block = _unzip(block)
        at_line = 0
        for _ in range(rows):
            for name, kind in channels:
                if name in names:
                    code = {HALF: "e", FLOAT: "f"}.get(kind, "I")
                    images[name].append(list(struct.unpack_from("<%d%s" % (width, code), block, at_line)))
                at_line += width * (2 if kind == HALF else 4)
    return width, ymax - ymin + 1


def channel_names(path):
    """Every channel's name in the file."""
    headers, _ = _headers(open(path, "rb").read())
    return {name for attributes in headers for name, _ in _channels(attributes["channels"])}


def read(path, names):
    """The named channels (e.g. "ViewLayer.DiffDir.R") as {name: rows}, plus (width, height)."""
    data = open(path, "rb").read()
    try:
        headers, at = _headers(data)
    except ValueError as error:
        raise ValueError("%s: %s" % (path, error))
    present = {name for attributes in headers for name, _ in _channels(attributes["channels"])}
    missing = [n for n in names if n not in present]
    if missing:
        raise ValueError("%s has no channel %s" % (path, ", ".join(missing)))
    multipart = len(headers) > 1 or "chunkCount" in headers[0]
    images = {n: [] for n in names}
    for attributes in headers:
        xmin, ymin, xmax, ymax = struct.unpack("<iiii", attributes["dataWindow"])
        lines = LINES_PER_BLOCK.get(attributes["compression"][0], 1)
        blocks = (struct.unpack("<i", attributes["chunkCount"])[0] if "chunkCount" in attributes
                  else (ymax - ymin + lines) // lines)
        offsets = struct.unpack_from("<%dQ" % blocks, data, at)
        at += 8 * blocks
        size = _read_part(data, attributes, offsets, multipart, set(names), images)
    return images, size
