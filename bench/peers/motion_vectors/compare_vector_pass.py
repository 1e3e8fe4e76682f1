# kiln motion layers against Blender's Vector pass on the pixels both cover:
#   /usr/bin/python3 compare_vector_pass.py KILN.exr BLENDER.exr
# kiln: --aovs beauty,P,motion --float. Prints the documented and the best-fitting channel mapping.
import OpenImageIO as oiio, numpy as np, sys
def rd(p):
    i=oiio.ImageInput.open(p); s=i.spec(); a=i.read_image(format='float'); return {n:a[:,:,k] for k,n in enumerate(s.channelnames)}
k=rd(sys.argv[1]); b=rd(sys.argv[2])
kA=k['A']; bA=b['ViewLayer.Combined.A']
m=(kA>0.99)&(bA>0.99)
print('coverage kiln',(kA>0.99).sum(),'blender',(bA>0.99).sum(),'both',m.sum(),'xor',((kA>0.99)^(bA>0.99)).sum())
B={c:b['ViewLayer.Vector.'+c] for c in 'XYZW'}
K={'bu':k['backward.u'],'bv':k['backward.v'],'-fu':-k['forward.u'],'-fv':-k['forward.v']}
print('documented mapping X=bu Y=bv Z=-fu W=-fv:')
for c,kk in zip('XYZW',['bu','bv','-fu','-fv']):
    d=np.abs(B[c][m]-K[kk][m]); print(f'  {c} vs {kk}: max {d.max():.4f} mean {d.mean():.4f}   (blender range {B[c][m].min():.3f}..{B[c][m].max():.3f})')
print('best candidate per Blender channel (all +-kiln channels):')
cand={}
for n in ['backward.u','backward.v','forward.u','forward.v']:
    cand['+'+n]=k[n]; cand['-'+n]=-k[n]
for c in 'XYZW':
    res=sorted((np.abs(B[c][m]-v[m]).mean(),np.abs(B[c][m]-v[m]).max(),n) for n,v in cand.items())
    print('  ',c,[(n,round(me,4),round(mx,4)) for me,mx,n in res[:2]])
# per-object split by kiln P.X (world x): mover x<0, spinner x>0
for name,sel in [('Mover',m&(k['P.X']<0)),('Spinner',m&(k['P.X']>0))]:
    print(name,sel.sum(),'means kiln bu,bv,-fu,-fv:',[round(float(K[q][sel].mean()),4) for q in ['bu','bv','-fu','-fv']],
          'blender X,Y,Z,W:',[round(float(B[c][sel].mean()),4) for c in 'XYZW'])
