# Issue 14, normals: how far the normals of real glTF assets are from the normals their own surface
# gives (area-weighted over the triangles around each position, positions welded): the normals a
# receiver could compute instead of receiving them. Prints, per primitive with normals and indices,
# the angle between the two (median, p90, p99, max) and the share within 2 and 5 degrees.
#   python3 bench/normal_agreement.py ../shared/samples/gltf/*/*.gltf > bench/results/normal_agreement.txt
import json, struct, sys, math, os
from collections import defaultdict
def load(path):
    g=json.load(open(path)); d=os.path.dirname(path)
    bufs=[open(os.path.join(d,b['uri']),'rb').read() for b in g['buffers']]
    def acc(i):
        a=g['accessors'][i]; bv=g['bufferViews'][a['bufferView']]; b=bufs[bv['buffer']]
        off=bv.get('byteOffset',0)+a.get('byteOffset',0); n=a['count']
        comps={'SCALAR':1,'VEC2':2,'VEC3':3,'VEC4':4}[a['type']]
        fmt={5126:'f',5123:'H',5125:'I',5121:'B'}[a['componentType']]; sz=struct.calcsize(fmt)
        stride=bv.get('byteStride',sz*comps)
        return [struct.unpack_from('<'+fmt*comps,b,off+k*stride) for k in range(n)]
    for m in g['meshes']:
        for p in m['primitives']:
            if 'NORMAL' not in p['attributes'] or 'indices' not in p: continue
            P=acc(p['attributes']['POSITION']); N=acc(p['attributes']['NORMAL']); I=[x[0] for x in acc(p['indices'])]
            key={}; wid=[]
            for v in P: wid.append(key.setdefault(tuple(round(c,6) for c in v), len(key)))
            acc_n=defaultdict(lambda:[0,0,0])
            for t in range(0,len(I),3):
                a,b,c=[P[I[t+k]] for k in range(3)]
                e1=[b[k]-a[k] for k in range(3)]; e2=[c[k]-a[k] for k in range(3)]
                n=[e1[1]*e2[2]-e1[2]*e2[1], e1[2]*e2[0]-e1[0]*e2[2], e1[0]*e2[1]-e1[1]*e2[0]]
                for k in range(3):
                    s=acc_n[wid[I[t+k]]]
                    for j in range(3): s[j]+=n[j]
            angs=[]
            for v in range(len(P)):
                s=acc_n[wid[v]]; l=math.sqrt(sum(x*x for x in s)) or 1; nn=N[v]; ln=math.sqrt(sum(x*x for x in nn)) or 1
                dot=sum(s[j]*nn[j] for j in range(3))/l/ln; angs.append(math.degrees(math.acos(max(-1,min(1,dot)))))
            angs.sort(); n=len(angs)
            print(path, m.get('name'), n, 'median %.2f p90 %.2f p99 %.2f max %.1f  within2 %.1f%% within5 %.1f%%'%(angs[n//2],angs[int(n*.9)],angs[int(n*.99)],angs[-1],100*sum(a<=2 for a in angs)/n,100*sum(a<=5 for a in angs)/n))
for f in sys.argv[1:]: load(f)
