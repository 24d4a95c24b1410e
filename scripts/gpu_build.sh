#!/usr/bin/env bash
# CUDA build of fecontact (docs/gpu.md): PETSc 3.18.5 with CUDA 13.0, built on a machine WITHOUT a
# GPU (Debian 12 with the packages of scripts/setup.sh), packed into a bundle that runs on a CUDA 13
# machine whose own Open MPI 4.1 and CUDA libraries it uses (the device machines of this workplace).
#
#   scripts/gpu_build.sh build        on the build machine (~15 min on 2 cores): downloads the PETSc
#                                     3.18.5 sources and the CUDA 13.0 compiler/headers/libraries as
#                                     PyPI wheels, patches PETSc for CUDA 13 (patch below), configures
#                                     and builds it, builds a `git archive HEAD` snapshot of fecontact
#                                     against it and writes .gpu/bundle.tar.xz + .gpu/fecontact-src.tar.gz
#   scripts/gpu_build.sh run ARGS...  on the GPU machine, from the repository root with .gpu carried:
#                                     unpacks both to /tmp/fcgpu (once) and runs `bin/fecontact ARGS`
#                                     there (paths such as input/... and meshes/... are the snapshot's)
#
# .gpu/ must be ignored (.git/info/exclude) and travels as a `carry` path (~27 MB).
# Environment: GPU_WORK (default ~/.cache/fecontact-gpu: downloads, CUDA, the PETSc tree and build,
# ~4 GB, never carried), NPROC.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
GPU="$ROOT/.gpu"
W="${GPU_WORK:-${XDG_CACHE_HOME:-$HOME/.cache}/fecontact-gpu}"
NPROC="${NPROC:-$(nproc)}"
CUDA_OPTS="-box_dm_mat_type aijcusparse -box_dm_vec_type cuda -wh_mat_type seqdensecuda -frames_mat_type seqaijcusparse -contact_vec_type seqcuda"

run_device() {
  local R=/tmp/fcgpu
  if [ ! -x "$R/bin/fecontact" ]; then
    rm -rf "$R" && mkdir -p "$R"
    tar xzf "$GPU/fecontact-src.tar.gz" -C "$R" && tar xJf "$GPU/bundle.tar.xz" -C "$R"
    # keep a carried Debian library only where the machine has none of that soname, except those
    # that must be Debian's (MUMPS, ScaLAPACK, Scotch, HDF5-openmpi and the OpenBLAS they were built with)
    for f in "$R"/rtlib/*; do
      so=$(basename "$f")
      case $so in libdmumps* | libmumps_common* | libscalapack* | libptscotch* | libscotch* | libhdf5_openmpi* | libsz* | libaec* | libblas.so.3 | liblapack.so.3 | libopenblas.so.0) continue ;; esac
      if ldconfig -p | grep -q "^[[:space:]]*$so "; then rm -f "$f"; fi
    done
  fi
  export LD_LIBRARY_PATH="$R/lib:$R/rtlib:/usr/local/cuda/lib64${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
  export OMPI_MCA_btl="${OMPI_MCA_btl:-self,vader}"
  cd "$R"
  mkdir -p out
  exec bin/fecontact "$@"
}

build() {
  mkdir -p "$W" "$GPU"
  grep -qx '/.gpu/' "$ROOT/.git/info/exclude" 2>/dev/null || echo "gpu_build: add /.gpu/ to .git/info/exclude so that .gpu/ is ignored" >&2

  # 1. PETSc 3.18.5 sources and CUDA 13.0 (nvcc 13.0.88, cuSPARSE 12.6.3.3, cuSOLVER 12.0.4.66, the
  #    versions of the device machines' /usr/local/cuda-13.0) from PyPI
  cd "$W"
  [ -f petsc-3.18.5.tar.gz ] || python3 -m pip download -q --no-deps --no-binary :all: petsc==3.18.5 -d .
  mkdir -p whl
  PLAT="--platform manylinux_2_27_x86_64 --platform manylinux_2_28_x86_64 --platform manylinux2014_x86_64 --platform manylinux_2_17_x86_64 --platform manylinux2010_x86_64 --platform manylinux_2_12_x86_64"
  WHEELS="nvidia-cuda-nvcc==13.0.88 nvidia-cuda-runtime==13.0.88 nvidia-cuda-crt==13.0.88 nvidia-nvvm==13.0.88 nvidia-cuda-cccl==13.0.85 nvidia-cublas==13.0.2.14 nvidia-cusparse==12.6.3.3 nvidia-cusolver==12.0.4.66 nvidia-nvjitlink==13.0.88 nvidia-cufft==12.0.0.61 nvidia-curand==10.4.0.35 nvidia-nvtx==13.0.85"
  [ "$(ls whl/*.whl 2>/dev/null | wc -l)" -ge 12 ] || python3 -m pip download -q --no-deps --only-binary=:all: $PLAT --python-version 3.11 -d whl $WHEELS
  C="$W/cuda/nvidia/cu13"
  if [ ! -x "$C/bin/nvcc" ]; then
    for w in whl/*.whl; do unzip -q -o "$w" -d cuda; done
    (cd "$C/lib" && for f in *.so.*; do ln -sf "$f" "${f%%.so.*}.so"; done && ln -sfn lib ../lib64)
    # PETSc links -lcuda; the driver's libcuda.so.1 is there at run time, a stub is enough to link
    mkdir -p "$C/lib/stubs" && echo 'void cuInit(void){}' >"$W/stub.c" &&
      gcc -shared -fPIC -Wl,-soname,libcuda.so.1 -o "$C/lib/stubs/libcuda.so" "$W/stub.c"
    (cd "$C/include" && for d in thrust cub cuda; do ln -sfn "cccl/$d" "$d"; done)
  fi
  export PATH="$C/bin:$PATH"

  # 2. PETSc 3.18.5 patched for CUDA 13 (the patch is at the end of this script)
  P="$W/petsc-3.18.5"
  if [ ! -f "$P/.cuda13-patched" ]; then
    rm -rf "$P" && tar xzf petsc-3.18.5.tar.gz
    petsc_patch | (cd "$P" && patch -p1 -s)
    touch "$P/.cuda13-patched"
  fi
  cd "$P"
  if [ ! -f arch-cuda/lib/libpetsc.so ]; then
    ./configure PETSC_ARCH=arch-cuda --with-cc=mpicc --with-cxx=mpicxx --with-fc=mpif90 \
      --with-debugging=0 COPTFLAGS=-O2 CXXOPTFLAGS=-O2 FOPTFLAGS=-O2 CUDAOPTFLAGS=-O2 \
      --with-shared-libraries --with-fortran-bindings=0 --with-x=0 \
      --with-cuda --with-cudac="$C/bin/nvcc" --with-cuda-arch=90 --with-cxx-dialect=17 --with-cuda-dialect=17 \
      --with-blas-lib=-lblas --with-lapack-lib=-llapack --with-scalapack-lib=-lscalapack-openmpi \
      --with-ptscotch-include=/usr/include/scotch --with-ptscotch-lib="-lptesmumps -lptscotch -lptscotcherr -lscotch -lscotcherr" \
      --with-mumps-include=/usr/include --with-mumps-lib="-ldmumps -lmumps_common -lpord" \
      --with-hdf5-include=/usr/include/hdf5/openmpi --with-hdf5-lib="-L/usr/lib/x86_64-linux-gnu/hdf5/openmpi -lhdf5"
    make PETSC_DIR="$P" PETSC_ARCH=arch-cuda MAKE_NP="$NPROC" all
  fi

  # 3. fecontact from a snapshot of HEAD (the working tree may be mid-edit), and the Table 1 meshes
  cd "$ROOT"
  git archive --format=tar.gz -o "$GPU/fecontact-src.tar.gz" HEAD
  git rev-parse HEAD >"$GPU/fecontact-src.commit"
  F="$W/fecontact"
  rm -rf "$F" && mkdir -p "$F" && tar xzf "$GPU/fecontact-src.tar.gz" -C "$F"
  (cd "$F" && scripts/make_meshes.sh)
  PKG_CONFIG_PATH="$P/arch-cuda/lib/pkgconfig" cmake -S "$F" -B "$F/build-cuda" -DCMAKE_BUILD_TYPE=Release >/dev/null
  cmake --build "$F/build-cuda" -j "$NPROC" --target fecontact

  # 4. the bundle: libpetsc, fecontact, the Debian libraries they need beyond glibc, the C++ runtime,
  #    Open MPI and CUDA (which the GPU machine has), and the Table 1 and cube_rest meshes
  B="$W/bundle"
  rm -rf "$B" && mkdir -p "$B/lib" "$B/bin" "$B/rtlib" "$B/meshes"
  cp "$P/arch-cuda/lib/libpetsc.so.3.18.5" "$B/lib/libpetsc.so.3.18"
  cp "$F/build-cuda/fecontact" "$B/bin/"
  ldd "$F/build-cuda/fecontact" | awk '/=>/ {print $1, $3}' | while read -r so path; do
    case $so in
    libc.so* | libm.so* | libdl.so* | libpthread.so* | librt.so* | libstdc++* | libgcc_s* | libcudart* | libcublas* | libcusparse* | libcusolver* | libcurand* | libcufft* | libnvJitLink* | libmpi.so* | libopen-rte* | libopen-pal* | libhwloc* | libevent* | libudev* | libpetsc*) ;;
    *) cp -L "$path" "$B/rtlib/$so" ;;
    esac
  done
  strip --strip-unneeded "$B/lib/"* "$B/rtlib/"* 2>/dev/null || true
  cp "$F"/meshes/table1_*.msh "$F"/meshes/cube_18.msh "$B/meshes/"
  tar cJf "$GPU/bundle.tar.xz" -C "$B" .
  ls -la "$GPU/bundle.tar.xz" "$GPU/fecontact-src.tar.gz"
  echo "gpu_build: done; on the GPU machine: bash scripts/gpu_build.sh run -options_file input/table1_18k.opts -constraint_scheme fast $CUDA_OPTS -use_gpu_aware_mpi 0"
}

# The patch of PETSc 3.18.5 for CUDA 13.0 / CCCL 3.0 (everything below the marker line):
# - configure: CUDA up to 13.0 (3.18 stops at 11.8), no libnvToolsExt (NVTX 3 is header only)
# - cuSPARSE 12.6 has no csrsv2: csrsv_spsv_compat.h emulates the csrsv2 calls of the LU/Cholesky/
#   ILU(k)/ICC(k) triangular solves with cusparseSpSV (values refreshed with SpSV_updateMatrix)
# - CCCL 3: no thrust::unary_function/binary_function, tuple.get<>(), thrust::identity, thrust/async
# - CUDA 13: cudaDeviceProp has no clockRate/memoryClockRate; cuFFT 12 dropped 3 status codes
petsc_patch() {
  cat <<'__PETSC_CUDA13_PATCH__'
--- a/config/BuildSystem/config/packages/cuda.py	2023-01-31 05:19:48.000000000 +0000
+++ b/config/BuildSystem/config/packages/cuda.py	2026-11-22 18:44:43.169313355 +0000
@@ -5,14 +5,14 @@
   def __init__(self, framework):
     config.package.Package.__init__(self, framework)
     self.minversion        = '7.5'
-    self.maxversion        = '11.8' # TODO: remove this line once we fix the code using cusparseDcsrsv2_solve() that is removed in cuda-12.0
+    self.maxversion        = '13.0' # fecontact GPU build: raised from 11.8 (see docs/gpu.md)
     self.versionname       = 'CUDA_VERSION'
     self.versioninclude    = 'cuda.h'
     self.requiresversion   = 1
     self.functions         = ['cublasInit','cufftDestroy']
     self.includes          = ['cublas.h','cufft.h','cusparse.h','cusolverDn.h','curand.h','thrust/version.h']
-    self.basicliblist      = [['libcudart.a','libnvToolsExt.a'],
-                              ['cudart.lib','nvToolsExt.lib']]
+    self.basicliblist      = [['libcudart.a'],
+                              ['cudart.lib']]
     self.mathliblist       = [['libcufft.a', 'libcublas.a','libcusparse.a','libcusolver.a','libcurand.a'],
                               ['cufft.lib','cublas.lib','cusparse.lib','cusolver.lib','curand.lib']]
     # CUDA provides 2 variants of libcuda.so (for access to CUDA driver API):
--- a/src/sys/logging/utils/eventlog.c	2022-10-01 04:12:21.000000000 +0000
+++ b/src/sys/logging/utils/eventlog.c	2026-11-22 18:44:43.173334335 +0000
@@ -726,7 +726,7 @@
 }
 
 #if defined(PETSC_HAVE_CUDA)
-  #include <nvToolsExt.h>
+  #include <nvtx3/nvToolsExt.h>
 #endif
 
 PetscErrorCode PetscLogEventBeginDefault(PetscLogEvent event, int t, PetscObject o1, PetscObject o2, PetscObject o3, PetscObject o4)
--- a/src/sys/classes/random/impls/curand/curand2.cu	2022-10-01 04:12:21.000000000 +0000
+++ b/src/sys/classes/random/impls/curand/curand2.cu	2026-11-22 19:03:14.461296740 +0000
@@ -4,7 +4,7 @@
 #include <thrust/iterator/counting_iterator.h>
 
 #if defined(PETSC_USE_COMPLEX)
-struct complexscalelw : public thrust::unary_function<thrust::tuple<PetscReal, size_t>, PetscReal> {
+struct complexscalelw {
   PetscReal rl, rw;
   PetscReal il, iw;
 
@@ -20,7 +20,7 @@
 };
 #endif
 
-struct realscalelw : public thrust::unary_function<PetscReal, PetscReal> {
+struct realscalelw {
   PetscReal l, w;
 
   realscalelw(PetscReal low, PetscReal width) : l(low), w(width) { }
--- a/src/mat/impls/dense/seq/cuda/densecuda.cu	2022-10-01 04:12:21.000000000 +0000
+++ b/src/mat/impls/dense/seq/cuda/densecuda.cu	2026-11-22 19:03:14.462028602 +0000
@@ -1080,7 +1080,7 @@
   PetscFunctionReturn(0);
 }
 
-struct petscshift : public thrust::unary_function<PetscScalar, PetscScalar> {
+struct petscshift {
   const PetscScalar shift_;
   petscshift(PetscScalar shift) : shift_(shift) { }
   __device__ PetscScalar operator()(PetscScalar x) { return x + shift_; }
@@ -1090,7 +1090,7 @@
 class strided_range {
 public:
   typedef typename thrust::iterator_difference<Iterator>::type difference_type;
-  struct stride_functor : public thrust::unary_function<difference_type, difference_type> {
+  struct stride_functor {
     difference_type stride;
     stride_functor(difference_type stride) : stride(stride) { }
     __device__ difference_type operator()(const difference_type &i) const { return stride * i; }
--- a/src/vec/vec/impls/seq/seqcuda/veccuda2.cu	2022-10-01 04:12:21.000000000 +0000
+++ b/src/vec/vec/impls/seq/seqcuda/veccuda2.cu	2026-11-22 19:03:14.466348863 +0000
@@ -1213,33 +1213,33 @@
   PetscFunctionReturn(0);
 }
 
-struct petscrealpart : public thrust::unary_function<PetscScalar, PetscReal> {
+struct petscrealpart {
   __host__ __device__ PetscReal operator()(const PetscScalar &x) { return PetscRealPart(x); }
 };
 
-struct petscrealparti : public thrust::unary_function<thrust::tuple<PetscScalar, PetscInt>, thrust::tuple<PetscReal, PetscInt>> {
-  __host__ __device__ thrust::tuple<PetscReal, PetscInt> operator()(const thrust::tuple<PetscScalar, PetscInt> &x) { return thrust::make_tuple(PetscRealPart(x.get<0>()), x.get<1>()); }
+struct petscrealparti {
+  __host__ __device__ thrust::tuple<PetscReal, PetscInt> operator()(const thrust::tuple<PetscScalar, PetscInt> &x) { return thrust::make_tuple(PetscRealPart(thrust::get<0>(x)), thrust::get<1>(x)); }
 };
 
-struct petscmax : public thrust::binary_function<PetscReal, PetscReal, PetscReal> {
+struct petscmax {
   __host__ __device__ PetscReal operator()(const PetscReal &x, const PetscReal &y) { return x < y ? y : x; }
 };
 
-struct petscmaxi : public thrust::binary_function<thrust::tuple<PetscReal, PetscInt>, thrust::tuple<PetscReal, PetscInt>, thrust::tuple<PetscReal, PetscInt>> {
+struct petscmaxi {
   __host__ __device__ thrust::tuple<PetscReal, PetscInt> operator()(const thrust::tuple<PetscReal, PetscInt> &x, const thrust::tuple<PetscReal, PetscInt> &y)
   {
-    return x.get<0>() < y.get<0>() ? thrust::make_tuple(y.get<0>(), y.get<1>()) : (x.get<0>() != y.get<0>() ? thrust::make_tuple(x.get<0>(), x.get<1>()) : (x.get<1>() < y.get<1>() ? thrust::make_tuple(x.get<0>(), x.get<1>()) : thrust::make_tuple(y.get<0>(), y.get<1>())));
+    return thrust::get<0>(x) < thrust::get<0>(y) ? thrust::make_tuple(thrust::get<0>(y), thrust::get<1>(y)) : (thrust::get<0>(x) != thrust::get<0>(y) ? thrust::make_tuple(thrust::get<0>(x), thrust::get<1>(x)) : (thrust::get<1>(x) < thrust::get<1>(y) ? thrust::make_tuple(thrust::get<0>(x), thrust::get<1>(x)) : thrust::make_tuple(thrust::get<0>(y), thrust::get<1>(y))));
   }
 };
 
-struct petscmin : public thrust::binary_function<PetscReal, PetscReal, PetscReal> {
+struct petscmin {
   __host__ __device__ PetscReal operator()(const PetscReal &x, const PetscReal &y) { return x < y ? x : y; }
 };
 
-struct petscmini : public thrust::binary_function<thrust::tuple<PetscReal, PetscInt>, thrust::tuple<PetscReal, PetscInt>, thrust::tuple<PetscReal, PetscInt>> {
+struct petscmini {
   __host__ __device__ thrust::tuple<PetscReal, PetscInt> operator()(const thrust::tuple<PetscReal, PetscInt> &x, const thrust::tuple<PetscReal, PetscInt> &y)
   {
-    return x.get<0>() > y.get<0>() ? thrust::make_tuple(y.get<0>(), y.get<1>()) : (x.get<0>() != y.get<0>() ? thrust::make_tuple(x.get<0>(), x.get<1>()) : (x.get<1>() < y.get<1>() ? thrust::make_tuple(x.get<0>(), x.get<1>()) : thrust::make_tuple(y.get<0>(), y.get<1>())));
+    return thrust::get<0>(x) > thrust::get<0>(y) ? thrust::make_tuple(thrust::get<0>(y), thrust::get<1>(y)) : (thrust::get<0>(x) != thrust::get<0>(y) ? thrust::make_tuple(thrust::get<0>(x), thrust::get<1>(x)) : (thrust::get<1>(x) < thrust::get<1>(y) ? thrust::make_tuple(thrust::get<0>(x), thrust::get<1>(x)) : thrust::make_tuple(thrust::get<0>(y), thrust::get<1>(y))));
   }
 };
 
@@ -1271,8 +1271,8 @@
     } catch (char *ex) {
       SETERRQ(PETSC_COMM_SELF, PETSC_ERR_LIB, "Thrust error: %s", ex);
     }
-    *m = res.get<0>();
-    *p = res.get<1>();
+    *m = thrust::get<0>(res);
+    *p = thrust::get<1>(res);
   } else {
     try {
 #if defined(PETSC_USE_COMPLEX)
@@ -1317,8 +1317,8 @@
     } catch (char *ex) {
       SETERRQ(PETSC_COMM_SELF, PETSC_ERR_LIB, "Thrust error: %s", ex);
     }
-    *m = res.get<0>();
-    *p = res.get<1>();
+    *m = thrust::get<0>(res);
+    *p = thrust::get<1>(res);
   } else {
     try {
 #if defined(PETSC_USE_COMPLEX)
@@ -1356,7 +1356,7 @@
   PetscFunctionReturn(0);
 }
 
-struct petscshift : public thrust::unary_function<PetscScalar, PetscScalar> {
+struct petscshift {
   const PetscScalar shift_;
   petscshift(PetscScalar shift) : shift_(shift) { }
   __host__ __device__ PetscScalar operator()(PetscScalar x) { return x + shift_; }
--- a/src/mat/impls/aij/mpi/mpicusparse/mpiaijcusparse.cu	2022-10-01 04:12:21.000000000 +0000
+++ b/src/mat/impls/aij/mpi/mpicusparse/mpiaijcusparse.cu	2026-11-22 19:03:14.467240165 +0000
@@ -133,7 +133,7 @@
     auto fzipp = thrust::make_zip_iterator(thrust::make_tuple(d_i.begin(), d_j.begin(), cusp->coo_p->begin()));
     auto ezipp = thrust::make_zip_iterator(thrust::make_tuple(d_i.end(), d_j.end(), cusp->coo_p->end()));
     auto mzipp = thrust::partition(thrust::device, fzipp, ezipp, IsNotOffDiagT<thrust::tuple<PetscInt, PetscInt, PetscInt>>(B->cmap->rstart, B->cmap->rend));
-    firstoffd  = mzipp.get_iterator_tuple().get<1>();
+    firstoffd  = thrust::get<1>(mzipp.get_iterator_tuple());
   }
   cusp->coo_nd = thrust::distance(d_j.begin(), firstoffd);
   cusp->coo_no = thrust::distance(firstoffd, d_j.end());
--- a/src/mat/impls/aij/seq/seqcusparse/aijcusparse.cu	2023-02-27 22:11:05.000000000 +0000
+++ b/src/mat/impls/aij/seq/seqcusparse/aijcusparse.cu	2026-11-22 19:46:20.481570213 +0000
@@ -13,13 +13,14 @@
 #undef VecType
 #include <../src/mat/impls/aij/seq/seqcusparse/cusparsematimpl.h>
 #include <thrust/adjacent_difference.h>
-#if PETSC_CPP_VERSION >= 14
+#if PETSC_CPP_VERSION >= 14 && !PETSC_PKG_CUDA_VERSION_GE(13, 0, 0) /* fecontact GPU build: thrust/async is gone in CCCL 3 */
   #define PETSC_HAVE_THRUST_ASYNC 1
   // thrust::for_each(thrust::cuda::par.on()) requires C++14
   #include <thrust/async/for_each.h>
 #endif
 #include <thrust/iterator/constant_iterator.h>
 #include <thrust/remove.h>
+#include <cuda/std/functional>
 #include <thrust/sort.h>
 #include <thrust/unique.h>
 
@@ -383,6 +384,9 @@
           v += nz;
         }
         loTriFactor->csrMat->values->assign(loTriFactor->AA_h, loTriFactor->AA_h + nzLower);
+#if PETSC_PKG_CUDA_VERSION_GE(13, 0, 0) /* fecontact GPU build: the SpSV emulation must refresh its values */
+        PetscCsrsvSpSVMarkDirty(loTriFactor->solveInfo);
+#endif
         PetscCall(PetscLogCpuToGpu(nzLower * sizeof(PetscScalar)));
       }
     } catch (char *ex) {
@@ -514,6 +518,9 @@
           PetscCall(PetscArraycpy(&(upTriFactor->AA_h[offset + 1]), v, nz));
         }
         upTriFactor->csrMat->values->assign(upTriFactor->AA_h, upTriFactor->AA_h + nzUpper);
+#if PETSC_PKG_CUDA_VERSION_GE(13, 0, 0) /* fecontact GPU build: the SpSV emulation must refresh its values */
+        PetscCsrsvSpSVMarkDirty(upTriFactor->solveInfo);
+#endif
         PetscCall(PetscLogCpuToGpu(nzUpper * sizeof(PetscScalar)));
       }
     } catch (char *ex) {
@@ -752,6 +759,10 @@
         PetscCheck(loTriFactor, PETSC_COMM_SELF, PETSC_ERR_COR, "Missing cusparseTriFactors");
         upTriFactor->csrMat->values->assign(AAUp, AAUp + a->nz);
         loTriFactor->csrMat->values->assign(AALo, AALo + a->nz);
+#if PETSC_PKG_CUDA_VERSION_GE(13, 0, 0) /* fecontact GPU build: the SpSV emulation must refresh its values */
+        PetscCsrsvSpSVMarkDirty(upTriFactor->solveInfo);
+        PetscCsrsvSpSVMarkDirty(loTriFactor->solveInfo);
+#endif
         PetscCall(PetscLogCpuToGpu(2 * (a->nz) * sizeof(PetscScalar)));
       }
       PetscCallCUDA(cudaFreeHost(AAUp));
@@ -3979,8 +3990,8 @@
 struct IJCompare {
   __host__ __device__ inline bool operator()(const thrust::tuple<PetscInt, PetscInt> &t1, const thrust::tuple<PetscInt, PetscInt> &t2)
   {
-    if (t1.get<0>() < t2.get<0>()) return true;
-    if (t1.get<0>() == t2.get<0>()) return t1.get<1>() < t2.get<1>();
+    if (thrust::get<0>(t1) < thrust::get<0>(t2)) return true;
+    if (thrust::get<0>(t1) == thrust::get<0>(t2)) return thrust::get<1>(t1) < thrust::get<1>(t2);
     return false;
   }
 };
@@ -3988,7 +3999,7 @@
 struct IJEqual {
   __host__ __device__ inline bool operator()(const thrust::tuple<PetscInt, PetscInt> &t1, const thrust::tuple<PetscInt, PetscInt> &t2)
   {
-    if (t1.get<0>() != t2.get<0>() || t1.get<1>() != t2.get<1>()) return false;
+    if (thrust::get<0>(t1) != thrust::get<0>(t2) || thrust::get<1>(t1) != thrust::get<1>(t2)) return false;
     return true;
   }
 };
@@ -4187,7 +4198,7 @@
       thrust::inclusive_scan(cusp->cooPerm_a->begin(), cusp->cooPerm_a->end(), cusp->cooPerm_a->begin(), thrust::plus<PetscInt>()); /*cooPerm_a=[0,0,1,2,3,4]*/
     }
     thrust::counting_iterator<PetscInt> search_begin(0);
-    thrust::upper_bound(d_i, nekey.get_iterator_tuple().get<0>(), /* binary search entries of [0,1,2,3,4,5,6) in ordered array d_i = [1,3,3,4,4], supposing A->rmap->n = 6. */
+    thrust::upper_bound(d_i, thrust::get<0>(nekey.get_iterator_tuple()), /* binary search entries of [0,1,2,3,4,5,6) in ordered array d_i = [1,3,3,4,4], supposing A->rmap->n = 6. */
                         search_begin, search_begin + A->rmap->n,  /* return in ii[] the index of last position in d_i[] where value could be inserted without violating the ordering */
                         ii.begin());                              /* ii = [0,1,1,3,5,5]. A leading 0 will be added later */
     PetscCall(PetscLogGpuTimeEnd());
@@ -4585,8 +4596,8 @@
 struct IJCompare4 {
   __host__ __device__ inline bool operator()(const thrust::tuple<int, int, PetscScalar, int> &t1, const thrust::tuple<int, int, PetscScalar, int> &t2)
   {
-    if (t1.get<0>() < t2.get<0>()) return true;
-    if (t1.get<0>() == t2.get<0>()) return t1.get<1>() < t2.get<1>();
+    if (thrust::get<0>(t1) < thrust::get<0>(t2)) return true;
+    if (thrust::get<0>(t1) == thrust::get<0>(t2)) return thrust::get<1>(t1) < thrust::get<1>(t2);
     return false;
   }
 };
@@ -4721,7 +4732,7 @@
 #if 0 //Errors on SUMMIT cuda 11.1.0
       PetscCallThrust(thrust::partition_copy(thrust::device,cci,cce,wPerm->begin(),p1,p2,thrust::identity<int>()));
 #else
-      auto pred = thrust::identity<int>();
+      auto pred = cuda::std::identity{}; // fecontact GPU build: thrust::identity is gone in CCCL 3
       PetscCallThrust(thrust::copy_if(thrust::device, cci, cce, wPerm->begin(), p1, pred));
       PetscCallThrust(thrust::remove_copy_if(thrust::device, cci, cce, wPerm->begin(), p2, pred));
 #endif
--- a/src/mat/impls/aij/seq/seqcusparse/cusparsematimpl.h	2022-10-01 04:12:21.000000000 +0000
+++ b/src/mat/impls/aij/seq/seqcusparse/cusparsematimpl.h	2026-11-22 19:03:03.709455606 +0000
@@ -67,7 +67,9 @@
   #endif
 #endif
 
-#if PETSC_PKG_CUDA_VERSION_GE(9, 0, 0)
+#if PETSC_PKG_CUDA_VERSION_GE(13, 0, 0) /* fecontact GPU build: csrsv2 is gone, emulate it with SpSV */
+  #include "csrsv_spsv_compat.h"
+#elif PETSC_PKG_CUDA_VERSION_GE(9, 0, 0)
   #define csrsvInfo_t              csrsv2Info_t
   #define cusparseCreateCsrsvInfo  cusparseCreateCsrsv2Info
   #define cusparseDestroyCsrsvInfo cusparseDestroyCsrsv2Info
--- a/src/mat/impls/aij/seq/seqcusparse/csrsv_spsv_compat.h	1970-01-01 00:00:00.000000000 +0000
+++ b/src/mat/impls/aij/seq/seqcusparse/csrsv_spsv_compat.h	2026-11-22 19:46:20.476966280 +0000
@@ -0,0 +1,111 @@
+/* fecontact GPU build (PETSc 3.18.5 on CUDA 13): cuSPARSE 12.6 (CUDA 13.0) removed the legacy
+   csrsv2 triangular solves that PETSc 3.18 uses for the LU/Cholesky/ILU(k) factors of
+   aijcusparse. This header emulates the few csrsv2 entry points PETSc calls with the generic
+   cusparseSpSV API (cusparse >= 11.3). The analysis keeps a CSR descriptor on the factor's arrays;
+   PETSc updates the factor's values in place without a new analysis (the "update values only"
+   branches of aijcusparse.cu): those branches mark the info dirty, and the next solve then calls
+   cusparseSpSV_updateMatrix with the new values. */
+#ifndef PETSC_CSRSV_SPSV_COMPAT_H
+#define PETSC_CSRSV_SPSV_COMPAT_H
+#include <cuda_runtime.h>
+#include <cusparse.h>
+
+struct PetscCsrsvSpSVInfo {
+  cusparseSpMatDescr_t A;
+  cusparseSpSVDescr_t  sv;
+  cusparseDnVecDescr_t x, y;
+  void                *buf, *tx, *ty;
+  int                  analyzed, dirty;
+};
+typedef PetscCsrsvSpSVInfo *csrsvInfo_t;
+
+static inline cusparseStatus_t cusparseCreateCsrsvInfo(csrsvInfo_t *info)
+{
+  *info = new PetscCsrsvSpSVInfo();
+  (*info)->analyzed = 0;
+  (*info)->dirty    = 0;
+  (*info)->buf = (*info)->tx = (*info)->ty = NULL;
+  return CUSPARSE_STATUS_SUCCESS;
+}
+
+static inline cusparseStatus_t cusparseDestroyCsrsvInfo(csrsvInfo_t info)
+{
+  if (!info) return CUSPARSE_STATUS_SUCCESS;
+  if (info->analyzed) {
+    cusparseSpSV_destroyDescr(info->sv);
+    cusparseDestroySpMat(info->A);
+    cusparseDestroyDnVec(info->x);
+    cusparseDestroyDnVec(info->y);
+  }
+  if (info->buf) cudaFree(info->buf);
+  if (info->tx) cudaFree(info->tx);
+  if (info->ty) cudaFree(info->ty);
+  delete info;
+  return CUSPARSE_STATUS_SUCCESS;
+}
+
+static inline void PetscCsrsvSpSVMarkDirty(csrsvInfo_t info)
+{
+  if (info) info->dirty = 1;
+}
+
+/* csrsv2_bufferSize: the SpSV buffer is owned by the info; PETSc's own buffer is a dummy */
+static inline cusparseStatus_t PetscCsrsvSpSV_bufferSize(cusparseHandle_t, cusparseOperation_t, int, int, const cusparseMatDescr_t, const void *, const int *, const int *, csrsvInfo_t, int *size)
+{
+  *size = 256;
+  return CUSPARSE_STATUS_SUCCESS;
+}
+
+static inline cusparseStatus_t PetscCsrsvSpSV_analysis(cusparseHandle_t handle, cusparseOperation_t op, int m, int nnz, const cusparseMatDescr_t descr, const void *vals, const int *rowptr, const int *colind, csrsvInfo_t info, cusparseSolvePolicy_t, void *, cudaDataType vt, size_t esize, const void *one)
+{
+  cusparseStatus_t  st;
+  cusparseFillMode_t fill = cusparseGetMatFillMode(descr);
+  cusparseDiagType_t diag = cusparseGetMatDiagType(descr);
+  cusparseIndexBase_t base = cusparseGetMatIndexBase(descr);
+  size_t             bsize = 0;
+  if (info->analyzed) return CUSPARSE_STATUS_SUCCESS; /* a repeated analysis on the same info: values are refreshed at each solve */
+  if ((st = cusparseCreateCsr(&info->A, m, m, nnz, (void *)rowptr, (void *)colind, (void *)vals, CUSPARSE_INDEX_32I, CUSPARSE_INDEX_32I, base, vt))) return st;
+  if ((st = cusparseSpMatSetAttribute(info->A, CUSPARSE_SPMAT_FILL_MODE, &fill, sizeof(fill)))) return st;
+  if ((st = cusparseSpMatSetAttribute(info->A, CUSPARSE_SPMAT_DIAG_TYPE, &diag, sizeof(diag)))) return st;
+  if (cudaMalloc(&info->tx, (m ? m : 1) * esize) != cudaSuccess) return CUSPARSE_STATUS_ALLOC_FAILED;
+  if (cudaMalloc(&info->ty, (m ? m : 1) * esize) != cudaSuccess) return CUSPARSE_STATUS_ALLOC_FAILED;
+  if ((st = cusparseCreateDnVec(&info->x, m, info->tx, vt))) return st;
+  if ((st = cusparseCreateDnVec(&info->y, m, info->ty, vt))) return st;
+  if ((st = cusparseSpSV_createDescr(&info->sv))) return st;
+  if ((st = cusparseSpSV_bufferSize(handle, op, one, info->A, info->x, info->y, vt, CUSPARSE_SPSV_ALG_DEFAULT, info->sv, &bsize))) return st;
+  if (cudaMalloc(&info->buf, bsize ? bsize : 1) != cudaSuccess) return CUSPARSE_STATUS_ALLOC_FAILED;
+  if ((st = cusparseSpSV_analysis(handle, op, one, info->A, info->x, info->y, vt, CUSPARSE_SPSV_ALG_DEFAULT, info->sv, info->buf))) return st;
+  info->analyzed = 1;
+  return CUSPARSE_STATUS_SUCCESS;
+}
+
+static inline cusparseStatus_t PetscCsrsvSpSV_solve(cusparseHandle_t handle, cusparseOperation_t op, int, int, const void *alpha, const cusparseMatDescr_t, const void *vals, const int *, const int *, csrsvInfo_t info, const void *x, void *y, cusparseSolvePolicy_t, void *, cudaDataType vt)
+{
+  cusparseStatus_t st;
+  if (!info->analyzed) return CUSPARSE_STATUS_NOT_INITIALIZED;
+  if (info->dirty) {
+    if ((st = cusparseSpSV_updateMatrix(handle, info->sv, (void *)vals, CUSPARSE_SPSV_UPDATE_GENERAL))) return st;
+    info->dirty = 0;
+  }
+  if ((st = cusparseDnVecSetValues(info->x, (void *)x))) return st;
+  if ((st = cusparseDnVecSetValues(info->y, y))) return st;
+  return cusparseSpSV_solve(handle, op, alpha, info->A, info->x, info->y, vt, CUSPARSE_SPSV_ALG_DEFAULT, info->sv);
+}
+
+#if defined(PETSC_USE_COMPLEX)
+  #if defined(PETSC_USE_REAL_SINGLE)
+    #define PETSC_CSRSV_VT CUDA_C_32F
+  #else
+    #define PETSC_CSRSV_VT CUDA_C_64F
+  #endif
+#else
+  #if defined(PETSC_USE_REAL_SINGLE)
+    #define PETSC_CSRSV_VT CUDA_R_32F
+  #else
+    #define PETSC_CSRSV_VT CUDA_R_64F
+  #endif
+#endif
+#define cusparseXcsrsv_buffsize(a, b, c, d, e, f, g, h, i, j)          PetscCsrsvSpSV_bufferSize(a, b, c, d, e, (const void *)(f), g, h, i, j)
+#define cusparseXcsrsv_analysis(a, b, c, d, e, f, g, h, i, j, k)       PetscCsrsvSpSV_analysis(a, b, c, d, e, (const void *)(f), g, h, i, j, k, PETSC_CSRSV_VT, sizeof(PetscScalar), (const void *)&PETSC_CUSPARSE_ONE)
+#define cusparseXcsrsv_solve(a, b, c, d, e, f, g, h, i, j, k, l, m, n) PetscCsrsvSpSV_solve(a, b, c, d, (const void *)(e), f, (const void *)(g), h, i, j, (const void *)(k), (void *)(l), m, n, PETSC_CSRSV_VT)
+#endif
--- a/src/sys/objects/device/impls/cupm/cupmdevice.cxx	2022-10-01 04:12:21.000000000 +0000
+++ b/src/sys/objects/device/impls/cupm/cupmdevice.cxx	2026-11-22 19:03:19.283363783 +0000
@@ -132,10 +132,10 @@
     PetscCall(PetscViewerASCIIPrintf(sviewer, "Total Global Memory (bytes): %zu\n", dprop_.totalGlobalMem));
     PetscCall(PetscViewerASCIIPrintf(sviewer, "Total Constant Memory (bytes): %zu\n", dprop_.totalConstMem));
     PetscCall(PetscViewerASCIIPrintf(sviewer, "Shared Memory Per Block (bytes): %zu\n", dprop_.sharedMemPerBlock));
-    PetscCall(PetscViewerASCIIPrintf(sviewer, "Multiprocessor Clock Rate (KHz): %d\n", dprop_.clockRate));
-    PetscCall(PetscViewerASCIIPrintf(sviewer, "Memory Clock Rate (KHz): %d\n", dprop_.memoryClockRate));
+    PetscCall(PetscViewerASCIIPrintf(sviewer, "Multiprocessor Clock Rate (KHz): %d\n", 0 /* fecontact GPU build: field removed in CUDA 13 */));
+    PetscCall(PetscViewerASCIIPrintf(sviewer, "Memory Clock Rate (KHz): %d\n", 0 /* removed in CUDA 13 */));
     PetscCall(PetscViewerASCIIPrintf(sviewer, "Memory Bus Width (bits): %d\n", dprop_.memoryBusWidth));
-    PetscCall(PetscViewerASCIIPrintf(sviewer, "Peak Memory Bandwidth (GB/s): %f\n", 2.0 * dprop_.memoryClockRate * (dprop_.memoryBusWidth / 8) / 1.0e6));
+    PetscCall(PetscViewerASCIIPrintf(sviewer, "Peak Memory Bandwidth (GB/s): %f\n", 2.0 * 0 /* removed in CUDA 13 */ * (dprop_.memoryBusWidth / 8) / 1.0e6));
     PetscCall(PetscViewerASCIIPrintf(sviewer, "Can map host memory: %s\n", dprop_.canMapHostMemory ? "PETSC_TRUE" : "PETSC_FALSE"));
     PetscCall(PetscViewerASCIIPrintf(sviewer, "Can execute multiple kernels concurrently: %s\n", dprop_.concurrentKernels ? "PETSC_TRUE" : "PETSC_FALSE"));
     PetscCall(PetscViewerASCIIPopTab(sviewer));
--- a/src/sys/error/err.c	2022-12-28 19:00:16.000000000 +0000
+++ b/src/sys/error/err.c	2026-11-22 19:27:57.113941380 +0000
@@ -795,18 +795,24 @@
     return "CUFFT_INVALID_SIZE";
   case CUFFT_UNALIGNED_DATA:
     return "CUFFT_UNALIGNED_DATA";
+#if CUFFT_VERSION < 12000 /* fecontact GPU build: gone in cuFFT 12 (CUDA 13) */
   case CUFFT_INCOMPLETE_PARAMETER_LIST:
     return "CUFFT_INCOMPLETE_PARAMETER_LIST";
+#endif
   case CUFFT_INVALID_DEVICE:
     return "CUFFT_INVALID_DEVICE";
+#if CUFFT_VERSION < 12000 /* fecontact GPU build: gone in cuFFT 12 (CUDA 13) */
   case CUFFT_PARSE_ERROR:
     return "CUFFT_PARSE_ERROR";
+#endif
   case CUFFT_NO_WORKSPACE:
     return "CUFFT_NO_WORKSPACE";
   case CUFFT_NOT_IMPLEMENTED:
     return "CUFFT_NOT_IMPLEMENTED";
+#if CUFFT_VERSION < 12000 /* fecontact GPU build: gone in cuFFT 12 (CUDA 13) */
   case CUFFT_LICENSE_ERROR:
     return "CUFFT_LICENSE_ERROR";
+#endif
   case CUFFT_NOT_SUPPORTED:
     return "CUFFT_NOT_SUPPORTED";
   default:
__PETSC_CUDA13_PATCH__
}

case "${1:-}" in
run)
  shift
  run_device "$@"
  ;;
build)
  build
  ;;
*)
  sed -n '2,17p' "$0"
  exit 1
  ;;
esac
