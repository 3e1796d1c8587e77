/* light.c: the frame's light set and the base colour rule (see light.h). */
#include "light.h"

#include "vecmath.h"

void light_env_init(struct light_env *env, const struct render_opts *o)
{
    env->n = o->n_lights;
    for (int i = 0; i < o->n_lights; i++) {
        vec3 l = v3_norm(o->lights[i].dir);
        env->dir[i][0] = (float)l.x;
        env->dir[i][1] = (float)l.y;
        env->dir[i][2] = (float)l.z;
        env->col[i][0] = (float)o->lights[i].color.x;
        env->col[i][1] = (float)o->lights[i].color.y;
        env->col[i][2] = (float)o->lights[i].color.z;
    }
}

void light_base_color(const struct material *m, const float *kd_override, int textured,
                      float base_out[3])
{
    const float *kd = kd_override ? kd_override : m->kd;
    for (int k = 0; k < 3; k++)
        base_out[k] = !kd_override && m->implicit && !textured ? LIGHT_DEFAULT_ALBEDO : kd[k];
}
