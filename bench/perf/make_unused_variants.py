# Variants of the 1M-triangle bench mesh and of the demo scene with unused data, written to the
# current folder. Usage: make_unused_variants.py MESH_1M.glb DEMO.gltf
import json, struct, shutil, sys, os
import numpy as np
from PIL import Image
src = sys.argv[1]; demo = sys.argv[2]
b = open(src, 'rb').read()
jl = struct.unpack('<I', b[12:16])[0]
doc = json.loads(b[20:20 + jl])
binoff = 20 + jl + 8
binary = b[binoff:]
def write(name, doc, binary):
    doc = json.loads(json.dumps(doc))
    doc['buffers'] = [{'byteLength': len(binary), 'uri': name + '.bin'}]
    open(name + '.bin', 'wb').write(binary)
    json.dump(doc, open(name + '.gltf', 'w'))
write('mesh_plain', doc, binary)
prim = doc['meshes'][0]['primitives'][0]
nv = doc['accessors'][prim['attributes']['POSITION']]['count']
extra = bytearray(binary)
while len(extra) % 4: extra.append(0)
def add(attr, comps, typ):
    off = len(extra)
    data = np.random.rand(nv * comps).astype(np.float32)
    if attr == 'TANGENT': data.reshape(-1, 4)[:, 3] = 1.0
    extra.extend(data.tobytes())
    doc['bufferViews'].append({'buffer': 0, 'byteOffset': off, 'byteLength': nv * comps * 4})
    doc['accessors'].append({'bufferView': len(doc['bufferViews']) - 1, 'componentType': 5126, 'count': nv, 'type': typ})
    prim['attributes'][attr] = len(doc['accessors']) - 1
add('TEXCOORD_0', 2, 'VEC2'); add('TEXCOORD_1', 2, 'VEC2'); add('TANGENT', 4, 'VEC4')
write('mesh_unused_attrs', doc, bytes(extra))
print('vertices', nv, 'extra bytes', len(extra) - len(binary))
# Demo scene plus a 4096x4096 RGBA image that a texture names but no material samples.
d = os.path.dirname(demo)
for f in ['cornell_box.bin', 'checker.png']: shutil.copy(os.path.join(d, f), f)
g = json.load(open(demo)); json.dump(g, open('demo_plain.gltf', 'w'))
Image.fromarray((np.random.rand(4096, 4096, 4) * 255).astype(np.uint8)).save('big.png')
g['images'].append({'name': 'big', 'uri': 'big.png', 'mimeType': 'image/png'})
g['textures'].append({'name': 'big', 'sampler': 0, 'source': len(g['images']) - 1})
json.dump(g, open('demo_unused_image.gltf', 'w'))
print('big.png bytes', os.path.getsize('big.png'))
