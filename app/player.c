/* The one frame path of the headless commands (player.h). */
#include "app/player.h"

#include <stdio.h>
#include <stdlib.h>

#include "app/pipeline.h"
#include "app/render_fog.h"
#include "app/render_frame.h"
#include "app/supersample.h"
#include "app/vdb_source.h"
#include "render/gl_context.h"
#include "sim/sim.h"

struct player {
  scene_config config;
  double fps, start_time;
  int width, height; /* the frames'; the sources draw supersample times finer */
  int supersample;
  frame_pixels fine; /* supersampled: the sources' frame, every output, made once */
  /* simulated: the pipeline and its context, and the fixed camera */
  gl_context *gl;
  pipeline *pipe;
  camera cam;
  /* static and played: a session (its own context); played: the sequence */
  render_session *session;
  vdb_sequence sequence;
  char gl_description[256];
};

void player_destroy(player *p) {
  if (!p) return;
  pipeline_destroy(p->pipe);
  gl_context_destroy(p->gl);
  render_session_destroy(p->session);
  if (p->sequence.count) vdb_sequence_destroy(&p->sequence);
  supersample_free(&p->fine);
  free(p);
}

static int create_simulated(player *p, const player_desc *desc, fog_error *err) {
  p->gl = gl_context_create(&(gl_context_desc){.kind = GL_CONTEXT_HEADLESS}, err);
  if (!p->gl) return 1;
  snprintf(p->gl_description, sizeof p->gl_description, "%s, %s, %s",
           gl_context_platform(p->gl), gl_context_version(p->gl), gl_context_renderer(p->gl));
  fog_error perr = {0};
  p->pipe = pipeline_create(&(pipeline_desc){.config = &p->config,
                                             .width = desc->width * p->supersample,
                                             .height = desc->height * p->supersample,
                                             .frame_seconds = 1.0 / desc->fps,
                                             .synchronous = desc->synchronous},
                            &perr);
  if (!p->pipe) {
    fog_error_pass(err, &perr);
    return 1;
  }
  return 0;
}

static int create_session(player *p, const player_desc *desc, fog_error *err) {
  if (desc->play && p->config.fog.model == FOG_MODEL_VOLUME &&
      render_fog_volume_sequence(&p->config, &p->sequence, err))
    return 1;
  fog_error ferr = {0};
  p->session = render_session_create(&p->config, desc->width * p->supersample,
                                     desc->height * p->supersample, &ferr);
  if (!p->session) {
    fog_error_pass(err, &ferr);
    return 1;
  }
  snprintf(p->gl_description, sizeof p->gl_description, "%s",
           render_session_gl_description(p->session));
  return 0;
}

player *player_create(const player_desc *desc, fog_error *err) {
  const bool simulated = desc->play && fog_model_table[desc->config->fog.model].pyramid;
  if (!(desc->width > 0 && desc->height > 0 && desc->fps > 0 && desc->start_time >= 0) ||
      (simulated && desc->start_time != 0)) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
             "player: %d x %d pixels at %g frames per second from %g s: expected sizes and a "
             "rate > 0, a time >= 0 (0 for a simulation, which starts there)", desc->width,
             desc->height, desc->fps, desc->start_time);
    return NULL;
  }
  player *p = calloc(1, sizeof *p);
  if (!p) {
    fog_fail(err, FOG_ERR_OUT_OF_MEMORY, "out of memory");
    return NULL;
  }
  p->config = *desc->config;
  p->width = desc->width, p->height = desc->height;
  p->supersample = desc->config->supersample;
  const long fine_width = (long)desc->width * p->supersample,
             fine_height = (long)desc->height * p->supersample;
  if (p->supersample < 1 || p->supersample > 4 || fine_width > PLAYER_MAX_SIDE ||
      fine_height > PLAYER_MAX_SIDE) {
    fog_fail(err, FOG_ERR_INVALID_ARGUMENT,
             "%s:%d: [render] supersample = %d draws %ldx%ld pixels for %dx%d: expected 1 to "
             "4, and at most %d a side (a smaller supersample, or a smaller size: --size or "
             "[render] width and height)", desc->config->path, desc->config->supersample_line,
             p->supersample, fine_width, fine_height, desc->width, desc->height,
             PLAYER_MAX_SIDE);
    free(p);
    return NULL;
  }
  if (p->supersample > 1) {
    float probe = 0.0f; /* every output: a caller may ask for any of them, frame by frame */
    const frame_pixels all = {.rgba = &probe, .transmittance = &probe, .depth = &probe,
                              .inscatter = &probe};
    if (supersample_buffers(&all, desc->width, desc->height, p->supersample, &p->fine, err)) {
      free(p);
      return NULL;
    }
  }
  p->fps = desc->fps;
  p->start_time = desc->start_time;
  scene_config_camera(&p->config, &p->cam); /* the session's scene takes the same one */
  /* (a fogmap config without a fogmap simulates from the emitters alone) */
  if (simulated ? create_simulated(p, desc, err) : create_session(p, desc, err)) {
    player_destroy(p);
    return NULL;
  }
  return p;
}

const char *player_gl_description(const player *p) { return p->gl_description; }

bool player_is_sequential(const player *p) { return p->pipe && pipeline_simulates(p->pipe); }

int player_skip(player *p, long frames, fog_error *err) {
  if (!p->pipe || frames <= 0) return 0; /* a session draws any frame n directly */
  fog_error perr = {0};
  if (pipeline_skip(p->pipe, frames, &perr)) {
    fog_error_pass(err, &perr);
    return 1;
  }
  return 0;
}

static int draw_frame(player *p, int n, const frame_pixels *out, fog_error *err);

int player_frame(player *p, int n, const frame_pixels *out, fog_error *err) {
  if (p->supersample == 1) return draw_frame(p, n, out, err);
  const frame_pixels fine = { /* only what out asks for is read back */
      .rgba = out->rgba ? p->fine.rgba : NULL,
      .transmittance = out->transmittance ? p->fine.transmittance : NULL,
      .depth = out->depth ? p->fine.depth : NULL,
      .inscatter = out->inscatter ? p->fine.inscatter : NULL};
  if (draw_frame(p, n, &fine, err)) return 1;
  supersample_reduce(&fine, p->width, p->height, p->supersample, (float)p->cam.far_plane,
                     out);
  return 0;
}

/* Frame n at the sources' size (supersample times the frames'). */
static int draw_frame(player *p, int n, const frame_pixels *out, fog_error *err) {
  if (p->pipe) {
    fog_error perr = {0};
    if (pipeline_frame(p->pipe, &p->cam, true, &perr) ||
        pipeline_read_frame(p->pipe, out, &perr)) {
      fog_error_pass(err, &perr);
      return 1;
    }
    return 0;
  }
  const scene_fog_config *f = &p->config.fog;
  const double time = p->start_time + (n - 1) / p->fps;
  {
    fog_error terr = {0};
    if (render_session_set_time(p->session, time, &terr)) {
      fog_error_pass(err, &terr);
      return 1;
    }
  }
  if (p->sequence.count) {
    /* Output frame n shows its time, between two VDB frames at vdb_fps, as a
     * VDB fogmap sequence plays (vdb_sequence_position). */
    int a = 0, b = 0;
    double w = 0.0;
    vdb_sequence_position(time * f->vdb_fps, p->sequence.count, f->vdb_loop, &a, &b, &w);
    if (render_fog_set_volume_time(render_session_fog(p->session), &p->config, &p->sequence,
                                   a, b, w, err))
      return 1;
  }
  fog_error ferr = {0};
  if (render_session_frame(p->session, out, &ferr)) {
    fog_error_pass(err, &ferr);
    return 1;
  }
  return 0;
}

const camera *player_camera(const player *p) { return &p->cam; }
