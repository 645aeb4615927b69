/* recorder: writes a rendered frame sequence to disk, one OpenEXR file per frame.
 *
 * Lifecycle (what `fogpipe record` and the headless `fogpipe demo` do):
 *   recorder_open()            checks the folder can be written (creates it if missing)
 *                              before any frame is rendered;
 *   recorder_complete_frames() the whole frames of this recording already there (for
 *                              --resume): each one decodes and carries the identity;
 *   recorder_write_frame()     one EXR per frame, `DIR/NAME.0001.exr` (1-based, 4 digits or
 *                              more), written to a temporary name and renamed by
 *                              image_write_exr, so no partial frame ever exists;
 *   recorder_write_preview()   optionally pipes the finished sequence through ffmpeg.
 * The progress display (a bar with ETA on a terminal, plain lines otherwise) is here too.
 * Errors are returned (status + message), never printed. */
#ifndef FOGPIPE_APP_RECORDER_H
#define FOGPIPE_APP_RECORDER_H

#include "app/out_folder.h"
#include "transform/fog_error.h"
#include "app/frame_exr.h"
#include "render/display.h"
#include <signal.h>
#include <stdbool.h>
#include <stdio.h>

typedef struct recorder_desc {
  const char *folder;  /* output folder; created (with parents) if missing */
  const char *name;    /* file name stem (NULL: "frame") */
  int width, height;
} recorder_desc;

typedef struct recorder {
  char folder[OUT_FOLDER_PATH_MAX];
  out_folder made; /* the folders recorder_open made (out_folder_undo removes them) */
  char name[128];
  int width, height;
  /* What the frames are made from (the caller sets it after opening): written into every
   * frame's header as the string attribute RECORDER_IDENTITY_ATTRIBUTE, so that --resume
   * can refuse a folder of another scene, size or frame rate. */
  char identity[256];
} recorder;

#define RECORDER_IDENTITY_ATTRIBUTE "fogpipeRecording"
#define RECORDER_PLANES FRAME_EXR_PLANES /* R G B A, transmittance, depth, Z, inscatter R G B */

/* One rendered frame as the GL pass reads it back: linear colour and alpha, transmittance
 * (fraction of the surface light that reaches the camera) and depth (distance along the
 * view ray to the first surface; +inf or a large value for the sky). Rows are bottom-up
 * when bottom_up is set (glReadPixels order) and are flipped to EXR's top-down order. */
typedef struct recorder_frame {
  const float *rgba;           /* width*height*4 interleaved */
  const float *transmittance;  /* width*height */
  const float *depth;          /* width*height */
  const float *inscatter;      /* width*height*3: rgb = transmittance surface + inscatter */
  /* The camera (camera_exr_matrices), written as worldToCamera and worldToNDC so that a
   * compositor can reproject the frame, and the Z channel's view axis. */
  float world_to_camera[16], world_to_ndc[16];
  camera view;
  bool bottom_up;
} recorder_frame;

/* Creates the folder if needed and proves it is writable by creating and removing a probe
 * file, so a read-only folder or a full disk is reported before any rendering. */
int recorder_open(recorder *rec, const recorder_desc *desc, fog_error *err);

/* Path of 1-based frame number `frame`: FOLDER/NAME.%04d.exr. */
void recorder_frame_path(const recorder *rec, int frame, char *path, size_t size);
/* The frame number of a file name NAME.####.exr (4 to 9 digits, as %04d writes them: no
 * leading zero past 4) in rec's folder, -1 for any other name: the files a run may clear
 * are the files it may write, which the check against the scene's inputs covers. */
int recorder_frame_number(const recorder *rec, const char *file);
/* Frame `frame`'s linear R, G, B read back into rgb (rec->width x rec->height x 3,
 * interleaved, top row first); non-zero with err set (unreadable, another size). */
int recorder_read_rgb(const recorder *rec, int frame, float *rgb, fog_error *err);

/* The last frame of the consecutive run first, first + 1, ... last already in the folder
 * (first - 1 when there is none). A frame counts when it decodes in every channel (a file
 * truncated by hand or by a broken disk is rendered again) and carries rec->identity.
 * -1 with err set when any frame of first..last there, before or after a gap, was made
 * from another recording (its identity differs, or it has none): resuming would rewrite
 * it or mix two sequences. */
int recorder_complete_frames(const recorder *rec, int first, int last, fog_error *err);
/* Whether a frame of first..last was recorded from another scene or settings (or carries
 * no identity): headers only, no pixels decoded (the stop's resume hint asks it of every
 * frame still ahead, which decoding took seconds a hundred frames). */
bool recorder_frames_foreign(const recorder *rec, int first, int last);

/* 0, or -1 with err naming the first frame of the folder outside first..last that was
 * recorded from another scene or settings (its identity differs from rec->identity, or it
 * has none): the run will leave it beside its own frames, one folder holding two
 * recordings (record warns; a bake's config rendering the frames a simulating scene left
 * off is one such folder, made on purpose). Frames inside the range are rewritten, frames
 * of this recording (a farm's other ranges) belong; a frame whose header cannot be read
 * is not judged. */
int recorder_check_other_frames(const recorder *rec, int first, int last, fog_error *err);

/* Removes every frame file of rec's name from its folder (NAME.NNNN.exr; nothing else):
 * for a folder that holds one throwaway recording at a time (the headless demo's
 * out/demo), so that a shorter run does not leave an earlier run's later frames beside
 * its own. Returns how many were removed. */
int recorder_remove_frames(const recorder *rec);

/* Removes the temporary files a killed run (SIGKILL, power loss) may have left beside
 * frames first..last: image_write_exr's ".NAME.NNNN.exr.tmp.PID.N". Only this range's: a
 * farm's other jobs write their own ranges into the folder at the same time, and their
 * temporaries are live. Returns how many were removed. */
int recorder_remove_stale_temporaries(const recorder *rec, int first, int last);

/* Writes frame number `frame` (1-based). Channels: R, G, B, A as half (as 32-bit float
 * where a value lies beyond half's range: *beauty_float, if not NULL, says which);
 * transmittance, depth (also as Z, what compositors read) and inscatter.R/G/B as 32-bit
 * float. `scratch` must hold RECORDER_PLANES*width*height floats (no allocation per
 * frame). On failure (disk full, folder removed) no partial file is left: a frame already
 * at the path (a --resume or range run's) stays as it was, whole. */
int recorder_write_frame(const recorder *rec, int frame, const recorder_frame *pixels,
                         float *scratch, bool *beauty_float, fog_error *err);

/* True when an `ffmpeg` executable is on PATH. */
bool recorder_have_ffmpeg(void);

/* Encodes frames 1..frame_count of the folder into an H.264 video at `fps` by reading each
 * EXR's R, G, B back and piping them through the display transform as 8-bit sRGB to ffmpeg
 * (so a resumed recording gets the same preview as an uninterrupted one). Written to a
 * temporary name and renamed; when *stop (NULL: never) becomes non-zero (a signal
 * handler's flag) it stops, and nothing is left at either name. */
int recorder_write_preview(const recorder *rec, int frame_count, double fps, const char *video_path,
                           const display_transform *display, const volatile sig_atomic_t *stop,
                           fog_error *err);

/* Progress of a sequence: on a terminal one line redrawn in place with a bar and the ETA;
 * otherwise one plain line per frame (logs stay readable). */
typedef struct recorder_progress {
  FILE *out;
  bool terminal;
  int total;     /* frames in the sequence */
  int first;     /* frames already complete when this run started */
  double start;  /* seconds (monotonic) when this run started rendering */
} recorder_progress;

void recorder_progress_begin(recorder_progress *p, FILE *out, int first, int total);
/* Called after frame `done` (1-based count of complete frames) is on disk. */
void recorder_progress_update(recorder_progress *p, int done);
/* Ends the in-place line on a terminal. */
void recorder_progress_end(recorder_progress *p);

#endif
