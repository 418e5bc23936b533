#!/usr/bin/env python3
"""A fragmented label map of the kind real segmentations are (and the phantom is not), written as
NIfTI-1: a ball of fat with a skin shell two voxels thick, fibroglandular tissue as thousands of
islands (blocky noise and single voxels), and a muscle slab on one image face that the ball
touches along thin contacts. Isotropic spacing; deterministic for a seed.

Usage: fragmented_labels.py N SPACING_MM OUT.nii[.gz] [SEED]
Labels: 0 outside, 1 fat, 2 fgt, 3 skin, 4 muscle. Prints the voxel count of each label.
"""
import gzip
import struct
import sys

import numpy as np

n=int(sys.argv[1]); h=float(sys.argv[2]); out=sys.argv[3]; seed=int(sys.argv[4]) if len(sys.argv)>4 else 1
rng=np.random.default_rng(seed)
x,y,z=np.meshgrid(*(np.arange(n)*h,)*3, indexing='ij')
c=n*h/2; r=np.sqrt((x-c)**2+(y-c)**2+(z-c)**2)
R=0.45*n*h
lab=np.zeros((n,n,n),np.uint8)
lab[r<R]=1
lab[(r<R)&(r>=R-2*h)]=3   # skin two voxels
# fgt islands: noise thresholded
noise=rng.random((n//4+1,)*3)
big=np.kron(noise,np.ones((4,4,4)))[:n,:n,:n]
fine=rng.random((n,n,n))
fgt=((big>0.6)&(fine>0.3))|(fine>0.985)
lab[(r<R-3*h)&fgt]=2
# muscle slab on the j = 0 face of the image
lab[:, :max(2,int(n*0.1)), :]=4
hdr=bytearray(348)
struct.pack_into('<i',hdr,0,348)
struct.pack_into('<8h',hdr,40,3,n,n,n,1,1,1,1)
struct.pack_into('<h',hdr,70,2)   # uint8
struct.pack_into('<h',hdr,72,8)
struct.pack_into('<8f',hdr,76,1,h,h,h,1,1,1,1)
struct.pack_into('<f',hdr,108,352.0)
struct.pack_into('<h',hdr,254,1)  # sform
for i,row in enumerate([[h,0,0,0],[0,h,0,0],[0,0,h,0]]):
    struct.pack_into('<4f',hdr,280+16*i,*row)
hdr[344:348]=b'n+1\0'
data=bytes(hdr)+b'\0'*4+lab.transpose(2,1,0).tobytes()
open(out, 'wb').write(gzip.compress(data, mtime=0) if out.endswith('.gz') else data)
print({k:int((lab==k).sum()) for k in range(5)})
