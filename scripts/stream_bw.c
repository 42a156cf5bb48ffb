/* One core's streaming bandwidth, STREAM-like (docs/performance.md,
 * section 3, the bytes-per-sphere-step bound): copy c = a, triad
 * a = b + 3 c and a read-only sum over arrays of SIZE MiB each (default
 * 1024, far beyond any cache), best of five passes. Timed in the thread's
 * CPU time, so that on a shared host the turns other tenants' processes
 * take on the core are not counted as slow memory. Bytes counted as the
 * loop names them (copy 16, triad 24, read 8 per element; a write also
 * reads its line first unless the compiler streams it).
 *
 *   gcc -O2 -march=native -o /tmp/stream_bw scripts/stream_bw.c && /tmp/stream_bw 1024
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
static double now(){struct timespec t;clock_gettime(CLOCK_THREAD_CPUTIME_ID,&t);return t.tv_sec+1e-9*t.tv_nsec;}
int main(int argc,char**argv){
  size_t mb = argc>1?atol(argv[1]):1024; size_t n = mb*(1<<20)/8;
  double *a=malloc(n*8),*b=malloc(n*8),*c=malloc(n*8);
  for(size_t i=0;i<n;i++){a[i]=1;b[i]=2;c[i]=0;}
  double bc=1e9,bt=1e9,br=1e9; volatile double sink=0;
  for(int r=0;r<5;r++){
    double t=now(); for(size_t i=0;i<n;i++) c[i]=a[i]; t=now()-t; if(t<bc)bc=t;
    t=now(); for(size_t i=0;i<n;i++) a[i]=b[i]+3.0*c[i]; t=now()-t; if(t<bt)bt=t;
    t=now(); double s0=0,s1=0,s2=0,s3=0; for(size_t i=0;i<n;i+=4){s0+=b[i];s1+=b[i+1];s2+=b[i+2];s3+=b[i+3];} double s=s0+s1+s2+s3; t=now()-t; sink+=s; if(t<br)br=t;
  }
  printf("array %zu MiB: copy %.1f GB/s, triad %.1f GB/s, read %.1f GB/s (counting read+write bytes, no write-allocate)\n",
    mb, 16.0*n/bc/1e9, 24.0*n/bt/1e9, 8.0*n/br/1e9);
  return 0;
}
