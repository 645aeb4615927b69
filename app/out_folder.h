/* Output folders the commands make for their results (record, bake, transform, import):
 * mkdir -p that remembers exactly which folders it made, and the undo a failed run calls so
 * that it leaves no folder behind that was not there before. */
#ifndef FOGPIPE_APP_OUT_FOLDER_H
#define FOGPIPE_APP_OUT_FOLDER_H

#include <stdbool.h>

#include "sim/sim.h"

enum { OUT_FOLDER_PATH_MAX = 1024 }; /* bytes with the terminating zero */

typedef struct out_folder {
  char path[OUT_FOLDER_PATH_MAX]; /* as given */
  /* made[i]: mkdir made the prefix path[0, i) (a component ends at i). By position, not by
   * cutting at slashes: "new/../old/sub" made "new" and ".../sub", never "old". */
  bool made[OUT_FOLDER_PATH_MAX];
  bool any; /* whether it made a folder at all */
} out_folder;

/* mkdir -p path into *folder (zeroed first). On failure (a name too long, a component that
 * is a file, no permission) the folders it made are removed again and err names the path.
 * A zero-initialised out_folder is one that made nothing. */
int out_folder_make(out_folder *folder, const char *path, fog_error *err);
/* Removes the folders out_folder_make made, innermost first, each only while it is empty:
 * files in them always stay, and a folder already gone is passed over. */
void out_folder_undo(const out_folder *folder);

#endif
