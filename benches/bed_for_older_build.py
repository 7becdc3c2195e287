"""A bed file for an older powderfmu build: the same bed with scene keys that build does not know removed.

An older build refuses a bed whose scene names a key it does not know (say `indenter_material`, or the
materials' `jkr_friction_limit`). For a side-by-side benchmark (benches/vs_lammps.py --compare-bed) the
bed's particles, contacts and walls must stay the same bits, so only the scene text of the payload is
rewritten; the envelope (src/envelope.rs: magic, version, payload length, FNV-1a 64 checksum) is resealed.
The keys removed must not matter to what is measured (`bed bench` sets the law, stiffness, interface
energy and rolling friction itself).

Usage: python3 benches/bed_for_older_build.py IN.bed OUT.bed KEY [KEY ...]

For issue 30's first binary (842bdd8) and a bench bed a current build prepared: `indenter_material
jkr_friction_limit forgetting_distance` (the last is a scene key since issue 30's twelfth round; that
build forgets a contact at its skin, as it always did).
"""

import json
import struct
import sys

HEADER, TRAILER = 20, 8  # magic (8), version (u32), payload length (u64); checksum (u64)


def varint(payload, i):
    """postcard's unsigned varint at byte i: (value, next byte)."""
    value, shift = 0, 0
    while True:
        c = payload[i]
        i += 1
        value |= (c & 0x7F) << shift
        shift += 7
        if c < 0x80:
            return value, i


def encode_varint(value):
    out = bytearray()
    while value >= 0x80:
        out.append((value & 0x7F) | 0x80)
        value >>= 7
    out.append(value)
    return bytes(out)


def fnv1a64(data):
    h = 0xCBF29CE484222325
    for x in data:
        h = ((h ^ x) * 0x100000001B3) & 0xFFFFFFFFFFFFFFFF
    return h


def main():
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    src, dst, keys = sys.argv[1], sys.argv[2], sys.argv[3:]
    data = open(src, "rb").read()
    if data[:5] != b"PFBED":
        sys.exit(f"{src}: not a bed file (no PFBED magic)")
    payload = data[HEADER:-TRAILER]
    # The payload's first field is the scene, a postcard String: its length, then UTF-8 JSON.
    n, start = varint(payload, 0)
    scene = json.loads(payload[start:start + n])
    removed = []
    for key in keys:
        for table in [scene] + [scene[m] for m in ("particle_particle", "particle_wall") if isinstance(scene.get(m), dict)]:
            if key in table:
                del table[key]
                removed.append(key)
    text = json.dumps(scene, separators=(",", ":")).encode()
    new = encode_varint(len(text)) + text + payload[start + n:]
    open(dst, "wb").write(data[:12] + struct.pack("<Q", len(new)) + new + struct.pack("<Q", fnv1a64(new)))
    print(f"{dst}: removed {', '.join(removed) or 'nothing'}")


if __name__ == "__main__":
    main()
