/* Output folders the commands make for their results (record, bake, transform, import):
 * mkdir -p that remembers the outermost folder it made, and the undo a failed run calls so
 * that it leaves no folder behind that was not there before. */
#ifndef FOGPIPE_APP_OUT_FOLDER_H
#define FOGPIPE_APP_OUT_FOLDER_H

#include <stddef.h>

#include "sim/sim.h"

enum { OUT_FOLDER_PATH_MAX = 1024 }; /* bytes with the terminating zero */

/* mkdir -p path; created (created_size bytes, "" to start) gets the outermost folder it
 * made. On failure (a name too long, a component that is a file, no permission) the
 * folders it made are removed again and err names the path. */
int out_folder_make(const char *path, char *created, size_t created_size, fog_error *err);
/* Removes path and its parents up to created (what out_folder_make made), innermost first,
 * as long as they are empty: files in them always stay. A folder already gone is passed
 * over. Nothing when created is "". */
void out_folder_remove(const char *path, const char *created);

#endif
