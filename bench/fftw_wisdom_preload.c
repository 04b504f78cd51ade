/* Preloaded (LD_PRELOAD) into both builds' benchmark processes by scripts/bench_before_after.py:
 * imports the FFTW wisdom file named by ERKN_PRELOAD_WISDOM before main and writes the
 * process's wisdom back at exit. FFTW_MEASURE times candidate plans, so two processes may plan
 * P1's transforms differently, and the plans differ in speed; with one wisdom file every process
 * after the first plans alike, whichever build it runs (the build before issue 19 cannot read
 * ERKN_FFTW_WISDOM). */
#include <fftw3.h>
#include <stdlib.h>

static void import_wisdom(void) __attribute__((constructor));
static void export_wisdom(void) __attribute__((destructor));

static void import_wisdom(void) {
  const char* file = getenv("ERKN_PRELOAD_WISDOM");
  if (file) fftw_import_wisdom_from_filename(file); /* (absent at first: nothing to import) */
}

static void export_wisdom(void) {
  const char* file = getenv("ERKN_PRELOAD_WISDOM");
  if (file) fftw_export_wisdom_to_filename(file);
}
