# hku-avia-2session, handheld: how far each session-2 scan's sensor is tilted from the session-1
# scans that saw the same place. One line a session-2 scan: its pitch in session 1's frame
# (T_s1_s2 x odometry) and the smallest tilt (angle between the sensors' z axes) to a session-1
# scan within 3 m and 30 deg of heading. The map's keyframes are session-1 scans, and their
# ScanContext++ descriptors are made in the sensor's frame, not a levelled one.
#   python3 hku_tilt.py [DATA]   (DATA: the data set's folder, default
#                                 shared/data/hku-avia-2session next to the checkout)
import math, sys
import os
ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', '..'))
H = (sys.argv[1] if len(sys.argv) > 1 else
     os.path.join(os.path.dirname(ROOT), 'shared', 'data', 'hku-avia-2session')).rstrip('/') + '/'
def M(l):
    v = list(map(float, l.split())); return [v[0:4], v[4:8], v[8:12], [0, 0, 0, 1]]
def mul(a, b): return [[sum(a[i][k] * b[k][j] for k in range(4)) for j in range(4)] for i in range(4)]
s1 = [M(l) for l in open(H + 'session1/odom_poses.txt') if l.strip()]
s2 = [M(l) for l in open(H + 'session2/odom_poses.txt') if l.strip()]
T = M(open(H + 'T_s1_s2.txt').read())
def tilt(A, B): return math.degrees(math.acos(max(-1, min(1, sum(A[r][2] * B[r][2] for r in range(3))))))
def hd(A, B): return (math.degrees(math.atan2(B[1][0], B[0][0]) - math.atan2(A[1][0], A[0][0])) + 180) % 360 - 180
def pitch(A): return math.degrees(math.asin(-A[2][0]))
for i in range(len(s2)):
    q = mul(T, s2[i]); best = None
    for j, k in enumerate(s1):
        d = math.hypot(k[0][3] - q[0][3], k[1][3] - q[1][3])
        if d < 3 and abs(hd(q, k)) < 30:
            t = tilt(q, k)
            if best is None or t < best[0]: best = (t, j, d, hd(q, k))
    print(i, 'pitch %.1f' % pitch(q), ('min tilt %.1f (s1 %d, %.2f m, heading %.1f)' % best) if best else 'no s1 scan within 3 m / 30 deg')
