/* Output files written into a staging folder first (a hidden one inside the output folder:
 * same file system), then moved in all or none, so that a failure at any point leaves the
 * output folder as it was: import's frames and sidecar, transform's levels and manifest. */
#ifndef FOGPIPE_APP_STAGED_MOVE_H
#define FOGPIPE_APP_STAGED_MOVE_H

/* The files of `staging` into `out`, all or none: a file of `out` they replace must be a
 * file (a folder or link in the way is refused before anything moves) and is kept aside
 * until every new one is in; the one .ini (a sidecar or manifest naming the others) goes
 * last. On a failure the replaced files come back. 0, or non-zero with the reason printed
 * as `fogpipe COMMAND: ...`. */
int staged_move_into_place(const char *command, const char *staging, const char *out);

/* Removes the staging folder and the files left in it (after a failure, or emptied). */
void staged_remove(const char *staging);

#endif
