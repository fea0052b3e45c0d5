#!/usr/bin/env python3
"""Writes the down-sampled regpair fixture: the first point of each CELL-metre voxel of
../shared/data/regpair/{source,target}.ply (binary PLY, x y z scalar_intensity), same format."""
import math, struct, sys

CELL = float(sys.argv[3]) if len(sys.argv) > 3 else 0.1


def read_ply(path):
    data = open(path, 'rb').read()
    end = data.index(b'end_header\n') + len(b'end_header\n')
    header = data[:end].decode()
    n = int(next(l for l in header.splitlines() if l.startswith('element vertex')).split()[2])
    props = [l.split()[2] for l in header.splitlines() if l.startswith('property')]
    assert props == ['x', 'y', 'z', 'scalar_intensity'], props
    return [struct.unpack_from('<4f', data, end + 16 * i) for i in range(n)]


def write_ply(path, pts):
    header = ('ply\nformat binary_little_endian 1.0\n'
              'comment down-sampled copy of small_gicp test data (MIT), see README.md\n'
              'element vertex %d\nproperty float x\nproperty float y\nproperty float z\n'
              'property float scalar_intensity\nend_header\n' % len(pts))
    with open(path, 'wb') as f:
        f.write(header.encode())
        for p in pts:
            f.write(struct.pack('<4f', *p))


def downsample(pts):
    seen, out = set(), []
    for p in pts:
        if not all(math.isfinite(v) for v in p[:3]):
            continue
        key = tuple(math.floor(v / CELL) for v in p[:3])
        if key not in seen:
            seen.add(key)
            out.append(p)
    return out


if __name__ == '__main__':
    src_dir, out_dir = sys.argv[1], sys.argv[2]
    for name in ('source', 'target'):
        pts = downsample(read_ply('%s/%s.ply' % (src_dir, name)))
        write_ply('%s/regpair_%s.ply' % (out_dir, name), pts)
        print(name, len(pts))
