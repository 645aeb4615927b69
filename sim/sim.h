/* fogpipe sim: where fog comes from. The public header of the sim library: fogmaps
 * (the 2D density grid, image I/O, designed fog), the FFT stable-fluid simulation and
 * OpenVDB import. Each part has its own header, included here. */
#ifndef FOGPIPE_SIM_H
#define FOGPIPE_SIM_H

#include "sim/atomic_file.h"
#include "sim/image.h"
#include "sim/fogmap.h"
#include "sim/fluid.h"
#include "sim/designed_fog.h"
#include "sim/vdb_import.h"
#include "sim/ray_box.h"

#endif
