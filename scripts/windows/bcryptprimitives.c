/* Wine 8.0 (Debian 12) has no bcryptprimitives.dll, which Rust's standard library for
   Windows imports for ProcessPrng (its random source, since Rust 1.78). For the tests under
   Wine only, this stand-in forwards ProcessPrng to RtlGenRandom (advapi32); it is never
   shipped. Built by scripts/build-windows --test. */
#include <windows.h>
#define SystemFunction036 NTAPI SystemFunction036
#include <ntsecapi.h>
#undef SystemFunction036

__declspec(dllexport) BOOL WINAPI ProcessPrng(PBYTE data, SIZE_T len) {
  while (len > 0) {
    ULONG n = len > 0x7fffffff ? 0x7fffffff : (ULONG)len;
    if (!RtlGenRandom(data, n)) return FALSE;
    data += n;
    len -= n;
  }
  return TRUE;
}
