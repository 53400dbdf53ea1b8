/*
 * The peg-in-hole's contact model — one body pair touching at up to HCM_MAX_POINTS
 * points — called from C through hcm-ffi, in one call per state (hcm_pair_load).
 *
 * Reads the peg's exported files (examples/blobs: the PM2 physics as TOML, IMPACT with
 * STEP friction; the 13-32-32-6 wrench residual in f32 and int8), decodes the blobs
 * into caller-owned HcmWrenchResidual storage, and evaluates the contact model at six
 * peg states: the physics at every contact point summed by Eq 1 plus the residual's
 * wrench on the peg about its centre of mass. It then shows the API refusing nine
 * points, an undecoded residual, the ball's blob as a wrench residual, a null point
 * array and an unknown friction law.
 *
 * A controller computes the contact points itself (its own collision geometry); here
 * they are a table: the firmware's manifold (hcm-firmware/src/peg/mod.rs, `manifold`)
 * at the peg states of hcm-firmware/src/peg/states.rs (rows of `hcm reproduce
 * peg-in-hole`'s S1), every float written with enough digits to be that f32 exactly.
 *
 * Every line is one record: a kind, then key=value fields (floats as their raw IEEE
 * bit patterns in hex, vectors comma-separated), then after " # " the same values
 * readable. tests/ffi_c_example.rs parses it and compares every value with Rust's own
 * evaluation through hcm_core's ContactModel::pair_load, bit for bit.
 *
 * Build (from the workspace root, after `cargo build -p hcm-ffi --release`):
 *   cc -std=c11 -O2 -Wall -Wextra -Ihcm-ffi/include -o target/peg_hcm \
 *      examples/c/peg_hcm.c target/release/libhcm_ffi.a -lpthread -ldl -lm
 * Run:
 *   target/peg_hcm examples/blobs
 */
#include "hcm.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* One peg state: the residual's 13 inputs (position (m), quaternion w, x, y, z (-),
   velocity (m/s), body-frame angular velocity (rad/s)) and the touching points. */
struct peg_state {
    const char *name;
    float input[HCM_WRENCH_RESIDUAL_INPUTS];
    HcmContactPoint points[HCM_MAX_POINTS];
    size_t count;
};

/* Points: {delta (m), rate (m/s), approach speed (m/s), max depth (m)}, normal (-),
   position (m), relative velocity (m/s), relative angular velocity (rad/s). */
static const struct peg_state STATES[] = {
    {.name = "wall_1_rising",
     .input = {2.2819426e-3f, -5.6122807e-28f, 8.103572e-2f,
               9.999905e-1f, 6.807587e-24f, 4.351504e-3f, 3.92951e-22f,
               9.826716e-2f, -3.2265746e-23f, -7.2367465e-1f,
               5.725107e-19f, 9.172621e-2f, 2.5485296e-17f},
     .points = {
         {{1.2208242e-5f, 1.01722606e-1f, 1.01722606e-1f, 0e0f},
          {-9.999621e-1f, -7.8595376e-22f, 8.702925e-3f},
          {1.2006104e-2f, 1e-2f, 4.999995e-2f},
          {9.542037e-2f, 2.7238207e-19f, -7.2456664e-1f},
          {7.9421354e-19f, 9.172621e-2f, 2.547935e-17f}},
         {{1.2208242e-5f, 1.01722606e-1f, 1.01722606e-1f, 0e0f},
          {-9.999621e-1f, -7.8595376e-22f, 8.702925e-3f},
          {1.2006104e-2f, -1e-2f, 4.999995e-2f},
          {9.542037e-2f, 2.7238207e-19f, -7.2456664e-1f},
          {7.9421354e-19f, 9.172621e-2f, 2.547935e-17f}},
     },
     .count = 2},
    {.name = "wall_1_peak",
     .input = {2.30755e-3f, -9.294297e-25f, 8.081859e-2f,
               9.9999005e-1f, 4.575953e-22f, 4.4673686e-3f, 2.910697e-20f,
               6.634326e-2f, -1.1151235e-20f, -7.2312313e-1f,
               7.489152e-18f, 1.7729716e0f, 3.8814859e-16f},
     .points = {
         {{3.2583863e-5f, 1.8316695e-2f, 1.8316695e-2f, 0e0f},
          {-9.999601e-1f, -5.821745e-20f, 8.934649e-3f},
          {1.2016292e-2f, 1e-2f, 4.9999855e-2f},
          {1.1702515e-2f, 4.0909983e-18f, -7.403365e-1f},
          {1.08536205e-17f, 1.7729716e0f, 3.8806828e-16f}},
         {{3.2583863e-5f, 1.8316695e-2f, 1.8316695e-2f, 0e0f},
          {-9.999601e-1f, -5.821745e-20f, 8.934649e-3f},
          {1.2016292e-2f, -1e-2f, 4.9999855e-2f},
          {1.1702515e-2f, 4.0909983e-18f, -7.403365e-1f},
          {1.08536205e-17f, 1.7729716e0f, 3.8806828e-16f}},
     },
     .count = 2},
    {.name = "wall_2_sliding",
     .input = {2.889541e-3f, -1.5588084e-21f, 5.752842e-2f,
               9.981581e-1f, 2.1852426e-19f, 6.0666863e-2f, 4.4357436e-18f,
               -3.5614282e-2f, 2.0306207e-18f, -9.734844e-1f,
               -1.0154678e-14f, 4.692073e0f, -7.594593e-14f},
     .points = {
         {{4.4833927e-5f, 5.2660003e-2f, 5.2660003e-2f, 0e0f},
          {-9.926391e-1f, -8.8816616e-18f, 1.2111024e-1f},
          {1.2022252e-2f, 1e-2f, 4.9997285e-2f},
          {-7.0950925e-2f, -8.206781e-16f, -1.0163357e0f},
          {-1.9319185e-14f, 4.692073e0f, -7.415249e-14f}},
         {{4.4833927e-5f, 5.2660003e-2f, 5.2660003e-2f, 0e0f},
          {-9.926391e-1f, -8.8816616e-18f, 1.2111024e-1f},
          {1.2022252e-2f, -9.999998e-3f, 4.9997285e-2f},
          {-7.0950925e-2f, -8.206781e-16f, -1.0163357e0f},
          {-1.9319185e-14f, 4.692073e0f, -7.415249e-14f}},
     },
     .count = 2},
    {.name = "wall_2_peak",
     .input = {2.7801616e-3f, 9.384272e-21f, 5.640294e-2f,
               9.981497e-1f, 3.5408216e-19f, 6.0804177e-2f, 3.2711461e-18f,
               -1.4022107e-1f, 5.76525e-18f, -8.8839495e-1f,
               6.308407e-15f, -7.084262e0f, 4.00661e-14f},
     .points = {
         {{7.1126036e-5f, 5.74857e-3f, 5.74857e-3f, 0e0f},
          {-9.9260575e-1f, -6.573247e-18f, 1.21383354e-1f},
          {1.20353e-2f, 1e-2f, 4.9995683e-2f},
          {-9.483039e-2f, 4.3825712e-16f, -8.228291e-1f},
          {1.1171074e-14f, -7.084262e0f, 3.8996275e-14f}},
         {{7.1126036e-5f, 5.74857e-3f, 5.74857e-3f, 0e0f},
          {-9.9260575e-1f, -6.573247e-18f, 1.21383354e-1f},
          {1.20353e-2f, -1e-2f, 4.9995683e-2f},
          {-9.483039e-2f, 4.3825712e-16f, -8.228291e-1f},
          {1.1171074e-14f, -7.084262e0f, 3.8996275e-14f}},
         {{1.2293458e-6f, -1.3245498e-1f, -1.3245498e-1f, 0e0f},
          {1e0f, 0e0f, 0e0f},
          {-1.2000615e-2f, -1e-2f, 1.7912544e-2f},
          {1.3245498e-1f, -1.4065093e-16f, -9.931058e-1f},
          {1.1171074e-14f, -7.084262e0f, 3.8996275e-14f}},
         {{1.2293458e-6f, -1.3245498e-1f, -1.3245498e-1f, 0e0f},
          {1e0f, 0e0f, 0e0f},
          {-1.2000615e-2f, 1e-2f, 1.7912544e-2f},
          {1.3245498e-1f, -1.4065093e-16f, -9.931058e-1f},
          {1.1171074e-14f, -7.084262e0f, 3.8996275e-14f}},
     },
     .count = 4},
    {.name = "flight",
     .input = {1e-3f, 0e0f, 8.95095e-2f,
               9.999905e-1f, 0e0f, 4.349986e-3f, 0e0f,
               1e-1f, 0e0f, -5.981e-1f,
               0e0f, 0e0f, 0e0f},
     .count = 0},
    {.name = "wall_2_fast",
     .input = {2.7801616e-3f, 9.384272e-21f, 5.640294e-2f,
               9.981497e-1f, 3.5408216e-19f, 6.0804177e-2f, 3.2711461e-18f,
               -1.4022107e-1f, 5.76525e-18f, -3e0f,
               6.308407e-15f, -7.084262e0f, 4.00661e-14f},
     .points = {
         {{7.1126036e-5f, 2.6206225e-1f, 2.6206225e-1f, 0e0f},
          {-9.9260575e-1f, -6.573247e-18f, 1.21383354e-1f},
          {1.20353e-2f, 1e-2f, 4.9995683e-2f},
          {-9.483039e-2f, 4.3825712e-16f, -2.9344342e0f},
          {1.1171074e-14f, -7.084262e0f, 3.8996275e-14f}},
         {{7.1126036e-5f, 2.6206225e-1f, 2.6206225e-1f, 0e0f},
          {-9.9260575e-1f, -6.573247e-18f, 1.21383354e-1f},
          {1.20353e-2f, -1e-2f, 4.9995683e-2f},
          {-9.483039e-2f, 4.3825712e-16f, -2.9344342e0f},
          {1.1171074e-14f, -7.084262e0f, 3.8996275e-14f}},
         {{1.2293458e-6f, -1.3245498e-1f, -1.3245498e-1f, 0e0f},
          {1e0f, 0e0f, 0e0f},
          {-1.2000615e-2f, -1e-2f, 1.7912544e-2f},
          {1.3245498e-1f, -1.4065093e-16f, -3.1047108e0f},
          {1.1171074e-14f, -7.084262e0f, 3.8996275e-14f}},
         {{1.2293458e-6f, -1.3245498e-1f, -1.3245498e-1f, 0e0f},
          {1e0f, 0e0f, 0e0f},
          {-1.2000615e-2f, 1e-2f, 1.7912544e-2f},
          {1.3245498e-1f, -1.4065093e-16f, -3.1047108e0f},
          {1.1171074e-14f, -7.084262e0f, 3.8996275e-14f}},
     },
     .count = 4},
};

/* The raw bits of a float. */
static uint32_t bits(float value) {
    uint32_t raw;
    memcpy(&raw, &value, sizeof raw);
    return raw;
}

/* Prints ` key=0x...,0x...` for `n` floats. */
static void print_floats(const char *key, const float *values, size_t n) {
    printf(" %s=", key);
    for (size_t i = 0; i < n; i++) {
        printf("%s0x%08x", i > 0 ? "," : "", (unsigned)bits(values[i]));
    }
}

/* The number after `key = ` on a line of `path`'s first contact; 0 on success. */
static int read_number(const char *path, const char *key, float *value) {
    FILE *file = fopen(path, "r");
    if (file == NULL) {
        perror(path);
        return 1;
    }
    char line[256], name[64];
    double number;
    int found = 0;
    while (!found && fgets(line, sizeof line, file) != NULL) {
        found = sscanf(line, " %63[a-z_] = %lf", name, &number) == 2 && strcmp(name, key) == 0;
    }
    fclose(file);
    if (!found) {
        fprintf(stderr, "%s: no %s\n", path, key);
        return 1;
    }
    *value = (float)number; /* rounded to float once, as the host rounds its f64 physics */
    return 0;
}

/* The peg's PM2: IMPACT (k, e, d_max, delta_max) with STEP friction (mu_s, mu_d, v_s,
   v_d), each parameter read as a double and rounded to float; 0 on success. */
static int read_pm2(const char *path, HcmPairPhysics *physics) {
    static const char *const LAW[4] = {"stiffness", "exponent", "max_damping",
                                       "full_damping_depth"};
    static const char *const FRICTION[4] = {"mu_static", "mu_dynamic", "v_static",
                                            "v_dynamic"};
    memset(physics, 0, sizeof *physics);
    physics->normal.base.kind = HCM_LAW_IMPACT;
    physics->friction.kind = HCM_FRICTION_STEP;
    for (int i = 0; i < 4; i++) {
        if (read_number(path, LAW[i], &physics->normal.base.parameters[i]) != 0 ||
            read_number(path, FRICTION[i], &physics->friction.parameters[i]) != 0) {
            return 1;
        }
    }
    printf("physics law=%u friction=%u", (unsigned)physics->normal.base.kind,
           (unsigned)physics->friction.kind);
    print_floats("law_parameters", physics->normal.base.parameters, 4);
    print_floats("friction_parameters", physics->friction.parameters, 4);
    const float *p = physics->normal.base.parameters, *f = physics->friction.parameters;
    printf(" # impact k=%.9g N/m^e e=%.9g d_max=%.9g N*s/m delta_max=%.9g m; step mu_s=%.9g"
           " mu_d=%.9g v_s=%.9g m/s v_d=%.9g m/s\n",
           p[0], p[1], p[2], p[3], f[0], f[1], f[2], f[3]);
    return 0;
}

/* The whole file at `path` in a malloc'd buffer, its length in *len; NULL on error. */
static uint8_t *read_file(const char *path, size_t *len) {
    FILE *file = fopen(path, "rb");
    if (file == NULL) {
        perror(path);
        return NULL;
    }
    uint8_t *bytes = NULL;
    size_t size = 0, capacity = 0, n;
    uint8_t chunk[4096];
    while ((n = fread(chunk, 1, sizeof chunk, file)) > 0) {
        if (size + n > capacity) {
            capacity = 2 * (size + n);
            uint8_t *grown = realloc(bytes, capacity);
            if (grown == NULL) {
                free(bytes);
                fclose(file);
                return NULL;
            }
            bytes = grown;
        }
        memcpy(bytes + size, chunk, n);
        size += n;
    }
    fclose(file);
    *len = size;
    return bytes;
}

/* Reads and decodes the wrench residual blob `folder/name` into *residual and prints
   its record; the status. */
static HcmStatus load_residual(const char *folder, const char *name, HcmWrenchResidual *residual) {
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", folder, name);
    size_t len = 0;
    uint8_t *blob = read_file(path, &len);
    HcmStatus status = blob == NULL ? HCM_STATUS_NULL_POINTER
                                    : hcm_wrench_residual_decode(blob, len, residual);
    free(blob);
    HcmWrenchResidualInfo info;
    if (status == HCM_STATUS_OK) {
        status = hcm_wrench_residual_info(residual, &info);
    }
    if (status != HCM_STATUS_OK) {
        fprintf(stderr, "%s: %s\n", path, hcm_status_name(status));
        return status;
    }
    printf("residual file=%s bytes=%zu quantisation=%u shape=%u-%u-%u-%u", name, len,
           (unsigned)info.quantisation, (unsigned)info.inputs, (unsigned)info.width,
           (unsigned)info.width, (unsigned)info.outputs);
    print_floats("min", info.envelope_min, HCM_WRENCH_RESIDUAL_INPUTS);
    print_floats("max", info.envelope_max, HCM_WRENCH_RESIDUAL_INPUTS);
    printf(" # %u hidden layers of %u; envelope z in [%.6g, %.6g] m, vz in [%.6g, %.6g] m/s\n",
           (unsigned)info.hidden_layers, (unsigned)info.width, info.envelope_min[2],
           info.envelope_max[2], info.envelope_min[9], info.envelope_max[9]);
    return HCM_STATUS_OK;
}

/* The contact model of the peg at `state` with `residual`, printed; the status. */
static HcmStatus evaluate(const HcmPairPhysics *physics, const HcmWrenchResidual *residual,
                          const char *weights, const struct peg_state *state) {
    HcmPairLoad load;
    /* Torques about the peg's centre of mass: its position, the first three inputs. */
    HcmStatus status = hcm_pair_load(physics, residual, state->points, state->count,
                                     state->input, state->input, &load);
    if (status != HCM_STATUS_OK) {
        return status;
    }
    printf("pair weights=%s state=%s count=%zu", weights, state->name, state->count);
    print_floats("input", state->input, HCM_WRENCH_RESIDUAL_INPUTS);
    for (size_t i = 0; i < state->count; i++) {
        const HcmContactPoint *p = &state->points[i];
        const float values[16] = {
            p->contact.depth,        p->contact.rate,         p->contact.approach_speed,
            p->contact.max_depth,    p->normal[0],            p->normal[1],
            p->normal[2],            p->position[0],          p->position[1],
            p->position[2],          p->relative_velocity[0], p->relative_velocity[1],
            p->relative_velocity[2], p->relative_angular_velocity[0],
            p->relative_angular_velocity[1], p->relative_angular_velocity[2],
        };
        char key[24];
        snprintf(key, sizeof key, "p%zu", i);
        print_floats(key, values, 16);
    }
    print_floats("force", load.force, 3);
    print_floats("torque", load.torque, 3);
    print_floats("normal_force", &load.normal_force, 1);
    printf(" points_used=%u residual_used=%d outside=%u", (unsigned)load.points_used,
           load.residual_used ? 1 : 0, (unsigned)load.outside_envelope);
    printf(" # F=(%.6g, %.6g, %.6g) N T=(%.6g, %.6g, %.6g) N*m sum f_n=%.6g N, %s\n",
           load.force[0], load.force[1], load.force[2], load.torque[0], load.torque[1],
           load.torque[2], load.normal_force,
           load.residual_used ? "physics + residual" : "physics alone");
    return HCM_STATUS_OK;
}

/* Prints a status check: what was tried, the code returned and its name. */
static void check(const char *what, HcmStatus status) {
    printf("check what=%s status=%d # %s\n", what, (int)status, hcm_status_name(status));
}

/* Bad arguments: each call must return its error code. */
static void show_refusals(const char *folder, const HcmPairPhysics *physics,
                          const HcmWrenchResidual *residual) {
    const struct peg_state *state = &STATES[3];
    HcmContactPoint nine[HCM_MAX_POINTS + 1];
    for (size_t i = 0; i < HCM_MAX_POINTS + 1; i++) {
        nine[i] = state->points[0];
    }
    HcmPairLoad load;
    check("nine_points", hcm_pair_load(physics, residual, nine, HCM_MAX_POINTS + 1, state->input,
                                       state->input, &load));
    static HcmWrenchResidual never; /* zeroed: never decoded */
    check("not_decoded", hcm_pair_load(physics, &never, state->points, state->count,
                                       state->input, state->input, &load));
    char path[1024];
    snprintf(path, sizeof path, "%s/bouncing_ball.f32.hcm", folder);
    size_t len = 0;
    uint8_t *ball = read_file(path, &len);
    check("ball_blob", ball == NULL ? HCM_STATUS_NULL_POINTER
                                    : hcm_wrench_residual_decode(ball, len, &never));
    free(ball);
    check("null_points", hcm_pair_load(physics, residual, NULL, state->count, state->input,
                                       state->input, &load));
    HcmPairPhysics unknown = *physics;
    unknown.friction.kind = 42;
    check("unknown_friction", hcm_pair_load(&unknown, residual, state->points, state->count,
                                            state->input, state->input, &load));
}

int main(int argc, char **argv) {
    const char *folder = argc > 1 ? argv[1] : "examples/blobs";
    static const char *const FILES[2] = {"peg_in_hole.f32.hcm", "peg_in_hole.int8.hcm"};
    static const char *const WEIGHTS[2] = {"f32", "int8"};
    char path[1024];

    HcmPairPhysics physics;
    snprintf(path, sizeof path, "%s/peg_in_hole.pm2.toml", folder);
    if (read_pm2(path, &physics) != 0 || hcm_pair_physics_validate(&physics) != HCM_STATUS_OK) {
        return 1;
    }
    static HcmWrenchResidual residuals[2]; /* static: 2 x HCM_WRENCH_RESIDUAL_SIZE bytes */
    for (int w = 0; w < 2; w++) {
        if (load_residual(folder, FILES[w], &residuals[w]) != HCM_STATUS_OK) {
            return 1;
        }
    }
    for (size_t s = 0; s < sizeof STATES / sizeof STATES[0]; s++) {
        for (int w = 0; w < 2; w++) {
            HcmStatus status = evaluate(&physics, &residuals[w], WEIGHTS[w], &STATES[s]);
            if (status != HCM_STATUS_OK) {
                fprintf(stderr, "%s: %s\n", STATES[s].name, hcm_status_name(status));
                return 1;
            }
        }
    }
    show_refusals(folder, &physics, &residuals[0]);
    return 0;
}
