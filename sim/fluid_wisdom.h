/* FFTW wisdom cache of the fluid solver (internal to the sim library). */
#ifndef FOGPIPE_SIM_FLUID_WISDOM_H
#define FOGPIPE_SIM_FLUID_WISDOM_H

#include <stddef.h>

/* $XDG_CACHE_HOME/fogpipe/fftw3f.wisdom, else $HOME/.cache/fogpipe/fftw3f.wisdom.
 * Returns 0 and writes the path, or non-zero when neither variable is set or the path
 * does not fit. */
int fluid_wisdom_path(char *path, size_t size);
/* Imports the cached wisdom into FFTW's (process-global) store; a missing or unreadable
 * file is not an error (returns 0 when something was imported). */
int fluid_wisdom_load(void);
/* Exports FFTW's wisdom to the cache (creating the folder, temp file + rename so a
 * reader never sees half a file). Failures are ignored (returns 0 on success). */
int fluid_wisdom_save(void);

#endif
