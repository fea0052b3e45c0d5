# Scores ltm_bench_localise --mode global on hku-avia-2session session 2 against session 1's map:
# the scans of the verified and the unverified cross-session pairs (truth: session-1 pose of scan i
# times the pair's ICP-refined T_A_B; a scan in both kinds counts as verified), and every scan
# against T_s1_s2 * session-2 odometry. A right answer: within 0.5 m / 2 deg.
#   hku_score.py ATTEMPTS.txt      (HKU_DATA: the data set's folder, default
#                                   shared/data/hku-avia-2session next to the checkout)
import math, os, sys
ROOT=os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)),'..','..','..'))
H=os.environ.get('HKU_DATA',os.path.join(os.path.dirname(ROOT),'shared','data','hku-avia-2session')).rstrip('/')+'/'
if len(sys.argv)!=2: sys.exit('usage: hku_score.py ATTEMPTS.txt')
att_file=sys.argv[1]
def m(v): return [[v[0],v[1],v[2],v[3]],[v[4],v[5],v[6],v[7]],[v[8],v[9],v[10],v[11]],[0,0,0,1]]
def mul(a,b): return [[sum(a[i][k]*b[k][j] for k in range(4)) for j in range(4)] for i in range(4)]
def inv(a):
    R=[[a[j][i] for j in range(3)] for i in range(3)]; t=[-sum(R[i][k]*a[k][3] for k in range(3)) for i in range(3)]
    return [R[0]+[t[0]],R[1]+[t[1]],R[2]+[t[2]],[0,0,0,1]]
s1=[m(list(map(float,l.split()))) for l in open(H+'session1/odom_poses.txt')]
s2=[m(list(map(float,l.split()))) for l in open(H+'session2/odom_poses.txt')]
T=m(list(map(float,open(H+'T_s1_s2.txt').read().split())))
att={}
for l in open(att_file):
    v=l.split(); att[int(v[0])]=(int(v[2]), m(list(map(float,v[3:15]))) if int(v[2]) else None)
def err(est,ref):
    d=mul(inv(ref),est); t=math.sqrt(sum(d[i][3]**2 for i in range(3)))
    c=max(-1,min(1,(d[0][0]+d[1][1]+d[2][2]-1)/2)); return t, math.degrees(math.acos(c))
ver={}; unv={}
for l in open(H+'verified_pairs.txt'):
    if not l.startswith('cross'): continue
    v=l.split(); i=int(v[2]); j=int(v[4]); ok=int(v[12]); TAB=m(list(map(float,v[13:25])))
    (ver if ok else unv).setdefault(j,mul(s1[i],TAB))
for j in list(unv):
    if j in ver: del unv[j]
for name,d in (('verified',ver),('unverified',unv)):
    right=wrong=none=0
    for j,truth in d.items():
        ok,est=att.get(j,(0,None))
        if not ok: none+=1; continue
        t,r=err(est,truth)
        if t<=0.5 and r<=2: right+=1
        else: wrong+=1; print(name,'off',j,round(t,2),'m',round(r,2),'deg')
    print('%s pairs: %d scans, right %d (%.1f %%), wrong %d, no pose %d'%(name,len(d),right,100.0*right/max(1,len(d)),wrong,none))
right=wrong=none=0
for j in range(len(s2)):
    ok,est=att.get(j,(0,None))
    if not ok: none+=1; continue
    t,r=err(est,mul(T,s2[j]))
    if t<=0.5 and r<=2: right+=1
    else:
        wrong+=1; print('vs odometry: off',j,round(t,2),'m',round(r,2),'deg')
print('every session-2 scan vs T_s1_s2 * odometry: %d scans, right %d, wrong %d, no pose %d'%(len(s2),right,wrong,none))
# The unverified pairs' own ICP did not converge well, so their poses are doubtful: the same
# scans also against T_s1_s2 * session-2 odometry (FAST-LIO2, cm-consistent over the session).
for name,d in (('verified',ver),('unverified',unv)):
    right=wrong=none=0
    for j in d:
        ok,est=att.get(j,(0,None))
        if not ok: none+=1; continue
        t,r=err(est,mul(T,s2[j]))
        if t<=0.5 and r<=2: right+=1
        else: wrong+=1
    print('%s pairs vs odometry: %d scans, right %d (%.1f %%), wrong %d, no pose %d'%(name,len(d),right,100.0*right/max(1,len(d)),wrong,none))
