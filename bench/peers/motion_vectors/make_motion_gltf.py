# A perspective camera over a quad sliding +X at 3 units/s and a quad spinning at 3 rad/s, keyed
# every 1/24 s (LINEAR), for comparing motion vectors with Blender: python3 make_motion_gltf.py OUT.gltf
import json, base64, struct, math
fps=24.0; K=49
times=[k/fps for k in range(K)]
# quad in XY plane, facing +Z, side 1
pos=[-0.5,-0.5,0, 0.5,-0.5,0, 0.5,0.5,0, -0.5,0.5,0]
nrm=[0,0,1]*4
idx=[0,1,2,0,2,3]
# object A: translate +X 1 unit/s starting x=-1.2,y=-0.3 ; object B: rotate about Z 1 rad/s at (1.0,0.4,0), also non-square (scale x 1.2,y 0.6)
trA=[]
for t in times: trA+= [-1.5+3*t, -0.3, 0.0]
rotB=[]
for t in times:
    a=3.0*t; rotB+=[0,0,math.sin(a/2),math.cos(a/2)]
blobs=[]
def add(fmt,data):
    b=struct.pack('<%d%s'%(len(data),fmt),*data)
    while len(b)%4: b+=b'\0'
    off=sum(len(x) for x in blobs); blobs.append(b); return off,len(b)
views=[]; acc=[]
def accessor(fmt,data,ctype,typ,count,mn=None,mx=None,target=None):
    off,ln=add(fmt,data)
    v={"buffer":0,"byteOffset":off,"byteLength":ln}
    if target: v["target"]=target
    views.append(v)
    a={"bufferView":len(views)-1,"componentType":ctype,"count":count,"type":typ}
    if mn is not None: a["min"]=mn; a["max"]=mx
    acc.append(a); return len(acc)-1
P=accessor('f',pos,5126,"VEC3",4,[-0.5,-0.5,0],[0.5,0.5,0],34962)
N=accessor('f',nrm,5126,"VEC3",4,target=34962)
I=accessor('H',idx,5123,"SCALAR",6,target=34963)
T=accessor('f',times,5126,"SCALAR",K,[0.0],[times[-1]])
TA=accessor('f',trA,5126,"VEC3",K)
RB=accessor('f',rotB,5126,"VEC4",K)
buf=b''.join(blobs)
g={"asset":{"version":"2.0"},"scene":0,
 "scenes":[{"nodes":[0,1,2]}],
 "nodes":[{"name":"Cam","camera":0,"translation":[0,0,5]},
          {"name":"Mover","mesh":0,"translation":[-1.2,-0.3,0]},
          {"name":"Spinner","mesh":1,"translation":[1.0,0.4,0],"scale":[1.2,0.6,1]}],
 "cameras":[{"type":"perspective","perspective":{"yfov":0.8,"aspectRatio":4/3,"znear":0.1,"zfar":100}}],
 "materials":[{"name":"m0","pbrMetallicRoughness":{"baseColorFactor":[0.8,0.3,0.2,1],"metallicFactor":0,"roughness Factor".replace(' ',''):1},"emissiveFactor":[1,1,1]}],
 "meshes":[{"primitives":[{"attributes":{"POSITION":P,"NORMAL":N},"indices":I,"material":0}]},
           {"primitives":[{"attributes":{"POSITION":P,"NORMAL":N},"indices":I,"material":0}]}],
 "animations":[{"name":"anim","channels":[{"sampler":0,"target":{"node":1,"path":"translation"}},{"sampler":1,"target":{"node":2,"path":"rotation"}}],
   "samplers":[{"input":T,"output":TA,"interpolation":"LINEAR"},{"input":T,"output":RB,"interpolation":"LINEAR"}]}],
 "accessors":acc,"bufferViews":views,
 "buffers":[{"byteLength":len(buf),"uri":"data:application/octet-stream;base64,"+base64.b64encode(buf).decode()}]}
import sys
json.dump(g,open(sys.argv[1] if len(sys.argv) > 1 else 'motion_test.gltf','w'))
print("ok",len(buf))
