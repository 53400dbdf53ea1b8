/*
 * The bouncing ball's hybrid contact model, called from C through hcm-ffi.
 *
 * Reads the ball's exported files (examples/blobs: the PM2 physics as TOML, the
 * residual blobs in f32 and int8), decodes the blobs into caller-owned HcmResidual
 * storage, and evaluates for a few contacts: the PM2 law, the law with two effects
 * added (the extended law), and the hybrid model (PM2 + residual) with each blob. It
 * then shows the API refusing a damaged blob, a cut blob, a null pointer and an
 * unknown law (a misaligned pointer cannot even be formed in portable C; the Rust
 * tests pass one).
 *
 * Every line is one record: a kind, then key=value fields (floats as their raw IEEE
 * bit patterns in hex, which is what a bit-identical comparison needs), then after
 * " # " the same values readable. tests/ffi_c_example.rs parses it and compares every
 * value with Rust's own evaluation through hcm_core.
 *
 * Build (from the workspace root, after `cargo build -p hcm-ffi --release`):
 *   cc -std=c11 -O2 -Wall -Wextra -Ihcm-ffi/include -o target/ball_hcm \
 *      examples/c/ball_hcm.c target/release/libhcm_ffi.a -lpthread -ldl -lm
 * Run:
 *   target/ball_hcm examples/blobs
 */
#include "hcm.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The raw bits of a float. */
static uint32_t bits(float value) {
    uint32_t raw;
    memcpy(&raw, &value, sizeof raw);
    return raw;
}

/* A law by its TOML name, with its parameters in the order HCM_LAW_* lists them. */
struct law_name {
    const char *name;
    HcmLawKind kind;
    const char *parameters[HCM_MAX_PARAMETERS];
};

static const struct law_name LAWS[] = {
    {"hertz", HCM_LAW_HERTZ, {"stiffness", "exponent"}},
    {"lankarani_nikravesh", HCM_LAW_LANKARANI_NIKRAVESH, {"stiffness", "exponent", "restitution"}},
    {"variable_stiffness", HCM_LAW_VARIABLE_STIFFNESS,
     {"surface_loading", "effective_modulus", "radius", "damping", "effective_mass"}},
    {"impact", HCM_LAW_IMPACT, {"stiffness", "exponent", "max_damping", "full_damping_depth"}},
    {"hunt_crossley", HCM_LAW_HUNT_CROSSLEY, {"stiffness", "exponent", "damping"}},
    {"flores", HCM_LAW_FLORES, {"stiffness", "exponent", "restitution"}},
};

/*
 * The first contact law of a PM2 file (`law = "..."` and its `name = value`
 * parameters), each parameter read as a double and rounded to float once, as the
 * host rounds its f64 physics for the controller. 0 on success.
 */
static int read_pm2(const char *path, HcmLaw *law) {
    FILE *file = fopen(path, "r");
    if (file == NULL) {
        perror(path);
        return 1;
    }
    const struct law_name *found = NULL;
    int seen = 0;
    char line[256];
    while (fgets(line, sizeof line, file) != NULL) {
        char key[64], text[64];
        double value;
        if (found == NULL && sscanf(line, " law = \"%63[a-z_]\"", text) == 1) {
            for (size_t i = 0; i < sizeof LAWS / sizeof LAWS[0]; i++) {
                if (strcmp(LAWS[i].name, text) == 0) {
                    found = &LAWS[i];
                }
            }
            if (found == NULL) {
                fprintf(stderr, "%s: unknown law \"%s\"\n", path, text);
                break;
            }
            memset(law, 0, sizeof *law);
            law->kind = found->kind;
        } else if (found != NULL && sscanf(line, " %63[a-z_] = %lf", key, &value) == 2) {
            for (int i = 0; i < HCM_MAX_PARAMETERS && found->parameters[i] != NULL; i++) {
                if (strcmp(found->parameters[i], key) == 0) {
                    law->parameters[i] = (float)value;
                    seen |= 1 << i;
                }
            }
        }
    }
    fclose(file);
    int count = 0;
    while (found != NULL && count < HCM_MAX_PARAMETERS && found->parameters[count] != NULL) {
        count++;
    }
    if (found == NULL || seen != (1 << count) - 1) {
        fprintf(stderr, "%s: no complete contact law\n", path);
        return 1;
    }
    printf("law kind=%u", (unsigned)law->kind);
    for (int i = 0; i < count; i++) {
        printf(" p%d=0x%08x", i, (unsigned)bits(law->parameters[i]));
    }
    printf(" # %s", found->name);
    for (int i = 0; i < count; i++) {
        printf(" %s=%.9g", found->parameters[i], law->parameters[i]);
    }
    printf("\n");
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

/*
 * Reads the blob at `path`, decodes it into *residual and prints its record; the blob
 * (malloc'd, its length in *len) or NULL after printing why.
 */
static uint8_t *load_residual(const char *path, const char *name, size_t *len,
                              HcmResidual *residual, HcmResidualInfo *info) {
    uint8_t *blob = read_file(path, len);
    HcmStatus status = blob == NULL ? HCM_STATUS_NULL_POINTER
                                    : hcm_residual_decode(blob, *len, residual);
    if (status == HCM_STATUS_OK) {
        status = hcm_residual_info(residual, info);
    }
    if (status != HCM_STATUS_OK) {
        fprintf(stderr, "%s: %s\n", path, hcm_status_name(status));
        free(blob);
        return NULL;
    }
    const float *lo = info->envelope_min, *hi = info->envelope_max;
    printf("residual file=%s bytes=%zu quantisation=%u min0=0x%08x min1=0x%08x min2=0x%08x"
           " max0=0x%08x max1=0x%08x max2=0x%08x # delta [%.6g, %.6g] m, rate [%.6g, %.6g]"
           " m/s, approach [%.9g, %.9g] m/s\n",
           name, *len, (unsigned)info->quantisation, (unsigned)bits(lo[0]),
           (unsigned)bits(lo[1]), (unsigned)bits(lo[2]), (unsigned)bits(hi[0]),
           (unsigned)bits(hi[1]), (unsigned)bits(hi[2]), lo[0], hi[0], lo[1], hi[1], lo[2],
           hi[2]);
    return blob;
}

/* Prints a status check: what was tried, the code returned and its name. */
static void check(const char *what, HcmStatus status) {
    printf("check what=%s status=%d # %s\n", what, (int)status, hcm_status_name(status));
}

static void print_contact(HcmContact c) {
    printf(" depth=0x%08x rate=0x%08x approach_speed=0x%08x max_depth=0x%08x",
           (unsigned)bits(c.depth), (unsigned)bits(c.rate), (unsigned)bits(c.approach_speed),
           (unsigned)bits(c.max_depth));
}

/* Evaluates and prints the law, the extended law and the hybrid model at `c`. */
static int evaluate(const HcmExtendedLaw *pm2, const HcmExtendedLaw *extended,
                    const HcmResidual residuals[2], HcmContact c) {
    static const char *const WEIGHTS[2] = {"f32", "int8"};
    float force;
    HcmStatus status = hcm_law_force(&pm2->base, c, &force);
    if (status != HCM_STATUS_OK) {
        return status;
    }
    printf("law_force");
    print_contact(c);
    printf(" force=0x%08x # delta=%.6g m rate=%.6g m/s approach=%.6g m/s -> %.9g N\n",
           (unsigned)bits(force), c.depth, c.rate, c.approach_speed, force);

    status = hcm_extended_law_force(extended, c, &force);
    if (status != HCM_STATUS_OK) {
        return status;
    }
    printf("extended_force");
    print_contact(c);
    printf(" force=0x%08x # %.9g N\n", (unsigned)bits(force), force);

    for (int w = 0; w < 2; w++) {
        HcmHybridForce out;
        status = hcm_hybrid_force(pm2, &residuals[w], c, &out);
        if (status != HCM_STATUS_OK) {
            return status;
        }
        printf("hybrid weights=%s", WEIGHTS[w]);
        print_contact(c);
        printf(" force=0x%08x physics=0x%08x residual_used=%d outside=%u"
               " # %.9g N = physics %.9g N %s\n",
               (unsigned)bits(out.force), (unsigned)bits(out.physics), out.residual_used ? 1 : 0,
               (unsigned)out.outside_envelope, out.force, out.physics,
               out.residual_used ? "+ residual" : "alone (residual off)");
    }
    return HCM_STATUS_OK;
}

/* Damaged blobs and bad arguments: each call must return its error code. */
static void show_refusals(uint8_t *blob, size_t len, HcmResidual *out) {
    blob[len / 2] ^= 0x10;
    check("bit_flip", hcm_residual_decode(blob, len, out));
    blob[len / 2] ^= 0x10;
    check("truncated", hcm_residual_decode(blob, len - 1, out));
    check("not_decoded", hcm_residual_info(out, &(HcmResidualInfo){0}));
    check("null_blob", hcm_residual_decode(NULL, len, out));
    float force;
    HcmLaw unknown = {42, {1.0f}};
    check("unknown_law", hcm_law_force(&unknown, (HcmContact){1e-5f, 0.0f, 1.0f, 1e-5f}, &force));
    check("decode_again", hcm_residual_decode(blob, len, out));
}

int main(int argc, char **argv) {
    const char *folder = argc > 1 ? argv[1] : "examples/blobs";
    static const char *const FILES[2] = {"bouncing_ball.f32.hcm", "bouncing_ball.int8.hcm"};
    char path[1024];

    HcmExtendedLaw pm2 = {0};
    snprintf(path, sizeof path, "%s/bouncing_ball.pm2.toml", folder);
    if (read_pm2(path, &pm2.base) != 0 || hcm_law_validate(&pm2.base) != HCM_STATUS_OK) {
        return 1;
    }
    /* The extended law: the PM2 plus viscous damping and adhesion, for illustration. */
    HcmExtendedLaw extended = pm2;
    extended.effect_count = 2;
    extended.effects[0] = (HcmEffect){HCM_EFFECT_VISCOUS_DAMPING, {25.0f}};
    extended.effects[1] = (HcmEffect){HCM_EFFECT_ADHESION, {2.0f}};
    for (uint32_t i = 0; i < extended.effect_count; i++) {
        printf("effect kind=%u p0=0x%08x # %.9g\n", (unsigned)extended.effects[i].kind,
               (unsigned)bits(extended.effects[i].parameters[0]), extended.effects[i].parameters[0]);
    }

    static HcmResidual residuals[2]; /* static: 2 × HCM_RESIDUAL_SIZE bytes */
    uint8_t *blobs[2] = {NULL, NULL};
    size_t lengths[2] = {0, 0};
    HcmResidualInfo info[2];
    for (int w = 0; w < 2; w++) {
        snprintf(path, sizeof path, "%s/%s", folder, FILES[w]);
        blobs[w] = load_residual(path, FILES[w], &lengths[w], &residuals[w], &info[w]);
        if (blobs[w] == NULL) {
            return 1;
        }
    }

    /* Contacts inside the f32 residual's envelope, one outside it in approach speed
       (the residual switches off) and one out of contact (zero force). */
    const float *lo = info[0].envelope_min, *hi = info[0].envelope_max;
    const float approach = lo[2] + 0.5f * (hi[2] - lo[2]);
    static const float FRACTIONS[4][2] = {{0.1f, 0.9f}, {0.3f, 0.6f}, {0.6f, 0.2f}, {0.9f, 0.45f}};
    HcmContact contacts[6];
    for (int i = 0; i < 4; i++) {
        float depth = lo[0] + FRACTIONS[i][0] * (hi[0] - lo[0]);
        float rate = lo[1] + FRACTIONS[i][1] * (hi[1] - lo[1]);
        contacts[i] = (HcmContact){depth, rate, approach, depth};
    }
    contacts[4] = contacts[1];
    contacts[4].approach_speed = 1.5f * approach;
    contacts[5] = (HcmContact){-1e-6f, contacts[1].rate, approach, 0.0f};
    for (int i = 0; i < 6; i++) {
        HcmStatus status = evaluate(&pm2, &extended, residuals, contacts[i]);
        if (status != HCM_STATUS_OK) {
            fprintf(stderr, "contact %d: %s\n", i, hcm_status_name(status));
            return 1;
        }
    }

    HcmResidual scratch;
    show_refusals(blobs[0], lengths[0], &scratch);
    free(blobs[0]);
    free(blobs[1]);
    return 0;
}
