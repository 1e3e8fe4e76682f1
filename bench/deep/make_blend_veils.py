#!/usr/bin/env python3
"""Writes blend_veils.gltf (argument: the path): six alpha-0.3 BLEND quads stacked in depth over an
opaque back quad, a point light and a camera at z = 6 -- the BLEND-heavy scene of the deep EXR
measurements (bench/deep/README.md)."""
import sys
import json, struct, base64
# Six tilted BLEND quads stacked in depth over an opaque floor quad; a point light; a camera at z = 6.
pos=[]; idx=[]; meshes=[]; nodes=[]; mats=[]; views=[]; accs=[]; buf=b''
def add(data, fmt, target, count, typ, ctype, mn=None, mx=None):
    global buf
    off=len(buf); b=struct.pack('<'+fmt*(len(data)), *data); buf+=b
    while len(buf)%4: buf+=b'\0'
    views.append({"buffer":0,"byteOffset":off,"byteLength":len(b),"target":target})
    a={"bufferView":len(views)-1,"componentType":ctype,"count":count,"type":typ}
    if mn: a["min"]=mn; a["max"]=mx
    accs.append(a); return len(accs)-1
def quad(x0,y0,x1,y1,z0,z1,mat,name):
    p=[x0,y0,z0, x1,y0,z0, x1,y1,z1, x0,y1,z1]
    pa=add(p,'f',34962,4,"VEC3",5126,[x0,y0,min(z0,z1)],[x1,y1,max(z0,z1)])
    ia=add([0,1,2,0,2,3],'I',34963,6,"SCALAR",5125)
    meshes.append({"primitives":[{"attributes":{"POSITION":pa},"indices":ia,"material":mat}]})
    nodes.append({"name":name,"mesh":len(meshes)-1})
mats.append({"name":"floor","pbrMetallicRoughness":{"baseColorFactor":[0.8,0.8,0.8,1],"metallicFactor":0}})
quad(-3,-3,3,3,-1,-1,0,"back")
cols=[[1,0.2,0.2],[0.2,1,0.2],[0.2,0.2,1],[1,1,0.2],[1,0.2,1],[0.2,1,1]]
for i,c in enumerate(cols):
    mats.append({"name":f"veil{i}","alphaMode":"BLEND","doubleSided":True,"pbrMetallicRoughness":{"baseColorFactor":c+[0.3],"metallicFactor":0}})
    x=-2.2+0.6*i; quad(x,-2+0.3*i,x+1.6,1.2+0.2*i,0.3*i,0.3*i+0.4,len(mats)-1,f"veil{i}")
nodes.append({"name":"lamp","extensions":{"KHR_lights_punctual":{"light":0}},"translation":[1,2,5]})
nodes.append({"name":"cam","camera":0,"translation":[0,0,6]})
doc={"asset":{"version":"2.0"},"extensionsUsed":["KHR_lights_punctual"],
 "extensions":{"KHR_lights_punctual":{"lights":[{"type":"point","intensity":60}]}},
 "cameras":[{"type":"perspective","perspective":{"yfov":0.75,"znear":0.1,"aspectRatio":16/9}}],
 "scene":0,"scenes":[{"nodes":list(range(len(nodes)))}],"nodes":nodes,"meshes":meshes,"materials":mats,
 "accessors":accs,"bufferViews":views,
 "buffers":[{"byteLength":len(buf),"uri":"data:application/octet-stream;base64,"+base64.b64encode(buf).decode()}]}
json.dump(doc, open(sys.argv[1] if len(sys.argv) > 1 else 'blend_veils.gltf', 'w'))
