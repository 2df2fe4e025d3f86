/* Test-only stand-in for bcryptprimitives.dll, which wine 8 lacks and every Windows 10 and 11
   has: Rust's standard library imports ProcessPrng from it (random hash seeds). Placed next to
   the test host under wine, never in an FMU. Fills the buffer from RtlGenRandom (advapi32's
   SystemFunction036), which wine has.
   x86_64-w64-mingw32-gcc -O2 -shared -o bcryptprimitives.dll bcryptprimitives.c -ladvapi32 */
#include <windows.h>

BOOLEAN WINAPI SystemFunction036(PVOID buffer, ULONG length); /* RtlGenRandom */

__declspec(dllexport) BOOL WINAPI ProcessPrng(PBYTE data, SIZE_T len) {
    while (len > 0) {
        ULONG chunk = len > 0x40000000 ? 0x40000000 : (ULONG)len;
        if (!SystemFunction036(data, chunk)) return FALSE;
        data += chunk;
        len -= chunk;
    }
    return TRUE;
}
