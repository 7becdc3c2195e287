/* A test fixture, never shipped in an FMU: Debian's wine 8.0 has no bcryptprimitives.dll, from which
   Rust's standard library (1.78 and later) imports ProcessPrng on Windows. This stand-in, placed beside
   the test executable, forwards ProcessPrng to RtlGenRandom (advapi32's SystemFunction036). */
#include <windows.h>
#include <ntsecapi.h>

__declspec(dllexport) BOOL WINAPI ProcessPrng(PBYTE data, SIZE_T len) {
    return RtlGenRandom(data, (ULONG)len);
}
