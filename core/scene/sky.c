/* core/scene/sky.c: the scene's sky: setting and parsing it, and its radiance in any direction.
 *
 * Uniform: the same radiance (W/(m^2 sr) per channel) from every direction of the sphere.
 *
 * Preetham: A. J. Preetham, P. Shirley, B. Smits, "A Practical Analytic Model for Daylight",
 * SIGGRAPH 1999. The luminance Y and the CIE chromaticities x, y of the sky in a direction at
 * zenith angle theta and angle gamma from the sun (at zenith angle theta_s) are
 *     Q(theta, gamma) = Q_z F_Q(theta, gamma) / F_Q(0, theta_s),   Q in {Y, x, y},
 * with the Perez et al. distribution
 *     F(theta, gamma) = (1 + A e^(B / cos theta)) (1 + C e^(D gamma) + E cos^2 gamma),
 * the coefficients A..E linear in the turbidity T and the zenith values Q_z of the paper's
 * appendix A.2 (written out in docs/reference.md). xyY goes to CIE XYZ and then to linear
 * sRGB (Rec. 709 primaries, D65) with the IEC 61966-2-1 matrix; negative channels are
 * clamped to 0. Y_z is in kcd/m^2; the model is multiplied by the sky's `scale`.
 */
#include "cg/scene.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define SKY_PI 3.14159265358979323846

static bool
finite_nonnegative(float v)
{
    return isfinite(v) && v >= 0.0f;
}

static const cg_light *
first_directional(const cg_scene *scene)
{
    for (int i = 0; i < scene->light_count; i++)
        if (scene->lights[i].type == CG_LIGHT_DIRECTIONAL)
            return &scene->lights[i];
    return NULL;
}

bool
cg_scene_set_sky(cg_scene *scene, const cg_sky *sky, cg_error *err)
{
    switch (sky->type) {
    case CG_SKY_NONE:
        break;
    case CG_SKY_UNIFORM:
        for (int c = 0; c < 3; c++)
            if (!finite_nonnegative(sky->radiance[c]))
                return cg_fail(err, CG_ERR_USAGE, "sky: radiance %g in channel %d, expected a finite value >= 0",
                               (double)sky->radiance[c], c);
        break;
    case CG_SKY_PREETHAM:
        if (!(sky->turbidity >= 1.7f && sky->turbidity <= 10.0f))
            return cg_fail(err, CG_ERR_USAGE,
                           "sky: turbidity %g, expected 1.7 to 10 (the range the Preetham model was fitted to)",
                           (double)sky->turbidity);
        if (!finite_nonnegative(sky->scale))
            return cg_fail(err, CG_ERR_USAGE, "sky: scale %g, expected a finite value >= 0", (double)sky->scale);
        if (!first_directional(scene))
            return cg_fail(err, CG_ERR_USAGE,
                           "%s: a Preetham sky takes its sun from the first directional light, and the scene has none",
                           scene->name);
        break;
    default:
        return cg_fail(err, CG_ERR_USAGE, "sky: unknown type %d", (int)sky->type);
    }
    scene->sky = *sky;
    return true;
}

/* Parses up to `max` comma-separated finite numbers; returns how many, or -1. */
static int
parse_numbers(const char *text, float *out, int max)
{
    int n = 0;
    const char *p = text;
    while (*p) {
        if (n == max)
            return -1;
        char *end;
        errno = 0;
        double v = strtod(p, &end);
        if (end == p || errno || !isfinite(v))
            return -1;
        out[n++] = (float)v;
        if (*end == '\0')
            break;
        if (*end != ',' || end[1] == '\0')
            return -1;
        p = end + 1;
    }
    return n;
}

bool
cg_sky_parse(const char *text, cg_sky *out, cg_error *err)
{
    memset(out, 0, sizeof *out);
    if (!strcmp(text, "none"))
        return true;
    if (!strncmp(text, "preetham", 8) && (text[8] == '\0' || text[8] == ':')) {
        float v[2] = { 3.0f, 1.0f };
        int n = text[8] == ':' ? parse_numbers(text + 9, v, 2) : 0;
        if (n < 0 || (text[8] == ':' && n == 0))
            return cg_fail(err, CG_ERR_USAGE, "sky '%s': expected preetham, preetham:TURBIDITY or "
                           "preetham:TURBIDITY,SCALE", text);
        out->type = CG_SKY_PREETHAM;
        out->turbidity = v[0];
        out->scale = v[1];
        if (!(out->turbidity >= 1.7f && out->turbidity <= 10.0f) || !finite_nonnegative(out->scale))
            return cg_fail(err, CG_ERR_USAGE, "sky '%s': turbidity 1.7 to 10 and a scale >= 0 expected", text);
        return true;
    }
    float v[3];
    int n = parse_numbers(text, v, 3);
    if (n != 1 && n != 3)
        return cg_fail(err, CG_ERR_USAGE, "sky '%s': expected none, R,G,B or L (radiance, W/(m^2 sr)), or "
                       "preetham[:TURBIDITY[,SCALE]]", text);
    if (n == 1)
        v[1] = v[2] = v[0];
    for (int c = 0; c < 3; c++)
        if (!finite_nonnegative(v[c]))
            return cg_fail(err, CG_ERR_USAGE, "sky '%s': radiance must be >= 0", text);
    out->type = CG_SKY_UNIFORM;
    memcpy(out->radiance, v, sizeof v);
    return true;
}

/* The Perez et al. distribution as the Preetham paper writes it. */
static double
perez(const double k[5], double cos_theta, double gamma)
{
    double cg = cos(gamma);
    return (1.0 + k[0] * exp(k[1] / cos_theta)) * (1.0 + k[2] * exp(k[3] * gamma) + k[4] * cg * cg);
}

bool
cg_sky_model_init(const cg_scene *scene, cg_sky_model *m, cg_error *err)
{
    memset(m, 0, sizeof *m);
    const cg_sky *sky = &scene->sky;
    m->type = sky->type;
    if (sky->type == CG_SKY_UNIFORM) {
        memcpy(m->radiance, sky->radiance, sizeof m->radiance);
        return true;
    }
    if (sky->type != CG_SKY_PREETHAM)
        return true;
    const cg_light *sun = first_directional(scene);
    if (!sun)
        return cg_fail(err, CG_ERR_USAGE,
                       "%s: a Preetham sky takes its sun from the first directional light, and the scene has none",
                       scene->name);
    double d[3] = { -sun->direction[0], -sun->direction[1], -sun->direction[2] };
    double len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if (!(len > 0.0))
        return cg_fail(err, CG_ERR_USAGE, "%s: light '%s' has no direction for the sky's sun", scene->name,
                       sun->name);
    for (int c = 0; c < 3; c++)
        m->sun[c] = (float)(d[c] / len);
    /* The model is fitted for the sun above the horizon: one below it gives the sky of a sun
     * on the horizon. */
    double theta_s = acos(fmin(fmax(d[1] / len, -1.0), 1.0));
    if (theta_s > 0.5 * SKY_PI)
        theta_s = 0.5 * SKY_PI;
    m->sun_zenith = (float)theta_s;
    double t = sky->turbidity;
    /* Appendix A.2: the Perez coefficients for Y, x and y, linear in T. */
    const double coef[3][5][2] = {
        { { 0.1787, -1.4630 }, { -0.3554, 0.4275 }, { -0.0227, 5.3251 }, { 0.1206, -2.5771 }, { -0.0670, 0.3703 } },
        { { -0.0193, -0.2592 }, { -0.0665, 0.0008 }, { -0.0004, 0.2125 }, { -0.0641, -0.8989 }, { -0.0033, 0.0452 } },
        { { -0.0167, -0.2608 }, { -0.0950, 0.0092 }, { -0.0079, 0.2102 }, { -0.0441, -1.6537 }, { -0.0109, 0.0529 } },
    };
    for (int q = 0; q < 3; q++)
        for (int k = 0; k < 5; k++)
            m->perez[q][k] = coef[q][k][0] * t + coef[q][k][1];
    /* Zenith luminance (kcd/m^2) and chromaticities. */
    double chi = (4.0 / 9.0 - t / 120.0) * (SKY_PI - 2.0 * theta_s);
    m->zenith[0] = (4.0453 * t - 4.9710) * tan(chi) - 0.2155 * t + 2.4192;
    const double mx[3][4] = { { 0.00166, -0.00375, 0.00209, 0.0 },
                              { -0.02903, 0.06377, -0.03202, 0.00394 },
                              { 0.11693, -0.21196, 0.06052, 0.25886 } };
    const double my[3][4] = { { 0.00275, -0.00610, 0.00317, 0.0 },
                              { -0.04214, 0.08970, -0.04153, 0.00516 },
                              { 0.15346, -0.26756, 0.06670, 0.26688 } };
    const double tv[3] = { t * t, t, 1.0 };
    const double sv[4] = { theta_s * theta_s * theta_s, theta_s * theta_s, theta_s, 1.0 };
    m->zenith[1] = m->zenith[2] = 0.0;
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 4; c++) {
            m->zenith[1] += tv[r] * mx[r][c] * sv[c];
            m->zenith[2] += tv[r] * my[r][c] * sv[c];
        }
    for (int q = 0; q < 3; q++)
        m->norm[q] = m->zenith[q] / perez(m->perez[q], 1.0, theta_s);
    m->scale = sky->scale;
    return true;
}

void
cg_sky_model_radiance(const cg_sky_model *m, const float dir[3], float rgb[3])
{
    rgb[0] = rgb[1] = rgb[2] = 0.0f;
    if (m->type == CG_SKY_UNIFORM) {
        memcpy(rgb, m->radiance, sizeof m->radiance);
        return;
    }
    if (m->type != CG_SKY_PREETHAM)
        return;
    double len = sqrt((double)dir[0] * dir[0] + (double)dir[1] * dir[1] + (double)dir[2] * dir[2]);
    double cos_theta = dir[1] / len;
    if (!(cos_theta > 0.0))
        return; /* below the horizon */
    double cos_gamma = (dir[0] * (double)m->sun[0] + dir[1] * (double)m->sun[1] + dir[2] * (double)m->sun[2]) / len;
    double gamma = acos(fmin(fmax(cos_gamma, -1.0), 1.0));
    double Y = m->norm[0] * perez(m->perez[0], cos_theta, gamma);
    double x = m->norm[1] * perez(m->perez[1], cos_theta, gamma);
    double y = m->norm[2] * perez(m->perez[2], cos_theta, gamma);
    if (!(Y > 0.0) || !(y > 0.0))
        return;
    double X = x / y * Y, Z = (1.0 - x - y) / y * Y;
    /* CIE XYZ to linear sRGB (IEC 61966-2-1). */
    double r = 3.2404542 * X - 1.5371385 * Y - 0.4985314 * Z;
    double g = -0.9692660 * X + 1.8760108 * Y + 0.0415560 * Z;
    double b = 0.0556434 * X - 0.2040259 * Y + 1.0572252 * Z;
    rgb[0] = (float)(fmax(r, 0.0) * m->scale);
    rgb[1] = (float)(fmax(g, 0.0) * m->scale);
    rgb[2] = (float)(fmax(b, 0.0) * m->scale);
}
