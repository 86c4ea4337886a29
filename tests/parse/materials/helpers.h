// Helpers shared by the material corpus: a 2-D vector struct with overloaded operators,
// a closure bundle, and small pattern functions. Included with #include "helpers.h".
#ifndef MATERIAL_HELPERS_H
#define MATERIAL_HELPERS_H

#define SQR(x) ((x) * (x))
#define SATURATE(x) clamp((x), 0.0, 1.0)
#define LOG_VALUE(name, ...) printf("%s = " name "\n", #name, __VA_ARGS__)

struct vector2 {
    float x;
    float y;
};

vector2 __operator__add__(vector2 a, vector2 b) { return vector2(a.x + b.x, a.y + b.y); }
vector2 __operator__sub__(vector2 a, vector2 b) { return vector2(a.x - b.x, a.y - b.y); }
vector2 __operator__mul__(vector2 a, float s) { return vector2(a.x * s, a.y * s); }
vector2 __operator__mul__(float s, vector2 a) { return vector2(a.x * s, a.y * s); }
vector2 __operator__mul__(vector2 a, vector2 b) { return vector2(a.x * b.x, a.y * b.y); }
vector2 __operator__div__(vector2 a, float s) { return vector2(a.x / s, a.y / s); }
vector2 __operator__neg__(vector2 a) { return vector2(-a.x, -a.y); }
int __operator__eq__(vector2 a, vector2 b) { return a.x == b.x && a.y == b.y; }
int __operator__neq__(vector2 a, vector2 b) { return !(a == b); }

float dot(vector2 a, vector2 b) { return a.x * b.x + a.y * b.y; }
float length(vector2 a) { return sqrt(dot(a, a)); }
vector2 floor(vector2 a) { return vector2(floor(a.x), floor(a.y)); }
vector2 fract(vector2 a) { return a - floor(a); }

// The closures of a layered material, carried through functions as one value.
struct Lobes {
    closure color base;
    closure color coat;
    color coat_weight;
    float opacity;
};

Lobes make_lobes(normal Nn, color albedo, float roughness)
{
    Lobes l;
    l.base = oren_nayar_diffuse_bsdf(Nn, albedo, roughness, "label", "base");
    l.coat = 0;
    l.coat_weight = color(0);
    l.opacity = 1;
    return l;
}

void add_coat(output Lobes l, normal Nn, float ior, float roughness)
{
    float Kr, Kt;
    fresnel(I, Nn, ior, Kr, Kt);
    l.coat = dielectric_bsdf(Nn, dPdu, color(1), color(0), roughness, roughness, ior, "ggx");
    l.coat_weight = color(Kr);
}

closure color combine(Lobes l)
{
    closure color c = l.coat_weight * l.coat + (1 - l.coat_weight) * l.base;
    return l.opacity * c + (1 - l.opacity) * transparent();
}

#endif
