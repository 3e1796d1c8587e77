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
    env->sky[0] = (float)o->ambient_sky.x;
    env->sky[1] = (float)o->ambient_sky.y;
    env->sky[2] = (float)o->ambient_sky.z;
    env->ground[0] = (float)o->ambient_ground.x;
    env->ground[1] = (float)o->ambient_ground.y;
    env->ground[2] = (float)o->ambient_ground.z;
    bool grey = env->sky[0] == env->sky[1] && env->sky[1] == env->sky[2] &&
                env->ground[0] == env->ground[1] && env->ground[1] == env->ground[2];
    for (int i = 0; i < env->n; i++)
        grey = grey && env->col[i][0] == env->col[i][1] && env->col[i][1] == env->col[i][2];
    env->grey = grey;
}

void light_use_camera(struct render_opts *o, const struct camera *c)
{
    vec3 back = v3_norm(v3_sub(c->eye, c->target));
    vec3 right = v3_norm(v3_cross(c->up, back));
    vec3 up = v3_cross(back, right);
    o->n_lights = 2;
    o->lights[0].dir = v3_add(v3_add(v3_scale(right, LIGHT_HEAD_RIGHT), v3_scale(up, LIGHT_HEAD_UP)),
                              v3_scale(back, LIGHT_HEAD_BACK));
    o->lights[0].color = v3(LIGHT_HEAD_COLOR, LIGHT_HEAD_COLOR, LIGHT_HEAD_COLOR);
    o->lights[1].dir = v3_add(v3_add(v3_scale(right, LIGHT_FILL_RIGHT), v3_scale(up, LIGHT_FILL_UP)),
                              v3_scale(back, LIGHT_FILL_BACK));
    o->lights[1].color = v3(LIGHT_FILL_COLOR, LIGHT_FILL_COLOR, LIGHT_FILL_COLOR);
    o->ambient_sky = v3(LIGHT_HEAD_SKY, LIGHT_HEAD_SKY, LIGHT_HEAD_SKY);
    o->ambient_ground = v3(LIGHT_HEAD_GROUND, LIGHT_HEAD_GROUND, LIGHT_HEAD_GROUND);
}

void light_base_color(const struct material *m, const float *kd_override, int textured,
                      float base_out[3])
{
    const float *kd = kd_override ? kd_override : m->kd;
    for (int k = 0; k < 3; k++)
        base_out[k] = !kd_override && m->implicit && !textured ? LIGHT_DEFAULT_ALBEDO : kd[k];
}
