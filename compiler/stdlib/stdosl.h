// stdosl.h: the part of Lobe's standard library written in the shading language itself, as
// OSL's stdosl.h does. Included automatically before every shader (embedded into the compiler
// at build time with the other built-in headers, see CMakeLists.txt). The functions
// implemented natively are in compiler/sema/builtins.cpp.

#ifndef STDOSL_H
#define STDOSL_H

// Constants
#define M_PI 3.1415926535897932
#define M_PI_2 1.5707963267948966
#define M_PI_4 0.7853981633974483
#define M_2_PI 0.6366197723675813
#define M_2PI 6.2831853071795865
#define M_4PI 12.566370614359173
#define M_2_SQRTPI 1.1283791670955126
#define M_E 2.7182818284590452
#define M_LN2 0.6931471805599453
#define M_LN10 2.3025850929940457
#define M_LOG2E 1.4426950408889634
#define M_LOG10E 0.4342944819032518
#define M_SQRT2 1.4142135623730950
#define M_SQRT1_2 0.7071067811865475

// hypot
float hypot(float a, float b) { return sqrt(a * a + b * b); }
float hypot(float a, float b, float c) { return sqrt(a * a + b * b + c * c); }

// clamp(x, lo, hi) = max(min(x, hi), lo) in this order, as OSL's (clamp(NaN, 0, 1) is NaN),
// per component for triples
int clamp(int x, int lo, int hi) { return max(min(x, hi), lo); }
float clamp(float x, float lo, float hi) { return max(min(x, hi), lo); }
color clamp(color x, color lo, color hi) { return max(min(x, hi), lo); }
point clamp(point x, point lo, point hi) { return max(min(x, hi), lo); }
vector clamp(vector x, vector lo, vector hi) { return max(min(x, hi), lo); }
normal clamp(normal x, normal lo, normal hi) { return max(min(x, hi), lo); }
color clamp(color x, float lo, float hi) { return clamp(x, color(lo), color(hi)); }
point clamp(point x, float lo, float hi) { return clamp(x, point(lo), point(hi)); }
vector clamp(vector x, float lo, float hi) { return clamp(x, vector(lo), vector(hi)); }
normal clamp(normal x, float lo, float hi) { return clamp(x, normal(lo), normal(hi)); }

// mix(a, b, t) = a * (1 - t) + b * t (OSL's are builtin ops: osl_builtin)
float mix(float a, float b, float t)[[int osl_builtin = 1]] { return a * (1 - t) + b * t; }
color mix(color a, color b, color t)[[int osl_builtin = 1]] { return a * (1 - t) + b * t; }
point mix(point a, point b, point t)[[int osl_builtin = 1]] { return a * (1 - t) + b * t; }
vector mix(vector a, vector b, vector t)[[int osl_builtin = 1]] { return a * (1 - t) + b * t; }
normal mix(normal a, normal b, normal t)[[int osl_builtin = 1]] { return a * (1 - t) + b * t; }
color mix(color a, color b, float t)[[int osl_builtin = 1]] { return a * (1 - t) + b * t; }
point mix(point a, point b, float t)[[int osl_builtin = 1]] { return a * (1 - t) + b * t; }
vector mix(vector a, vector b, float t)[[int osl_builtin = 1]] { return a * (1 - t) + b * t; }
normal mix(normal a, normal b, float t)[[int osl_builtin = 1]] { return a * (1 - t) + b * t; }
closure color mix(closure color a, closure color b, float t) { return (1 - t) * a + t * b; }
closure color mix(closure color a, closure color b, color t) { return (1 - t) * a + t * b; }

// Closure overloads defined in the language, as OSL's stdosl.h defines them: each forwards to
// the registry's closure, so it prints (and renders) as that closure.
closure color microfacet(string distribution, normal N, float alpha, float eta, int refr) {
  return microfacet(distribution, N, vector(0), alpha, alpha, eta, refr);
}
closure color reflection(normal N) { return reflection(N, 0.0); }

// Directions
normal faceforward(normal N, vector I, normal Nref) { return (dot(I, Nref) > 0) ? -N : N; }
normal faceforward(normal N, vector I) { return faceforward(N, I, Ng); }
vector reflect(vector I, vector N) { return I - 2 * dot(N, I) * N; }
vector refract(vector I, vector N, float eta) {
  float IdotN = dot(I, N);
  float k = 1 - eta * eta * (1 - IdotN * IdotN);
  return (k < 0) ? vector(0, 0, 0) : (eta * I - (eta * IdotN + sqrt(k)) * N);
}

// Dielectric Fresnel: reflected and transmitted fractions and directions, as OSL computes them.
void fresnel(vector I, normal N, float eta, output float Kr, output float Kt, output vector R,
             output vector T) {
  float sqr(float x) { return x * x; }
  float c = dot(I, N);
  if (c < 0) c = -c;
  R = reflect(I, N);
  float g = 1.0 / sqr(eta) - 1 + c * c;
  if (g >= 0) {
    g = sqrt(g);
    float beta = g - c;
    float F = (c * (g + c) - 1) / (c * beta + 1);
    F = 0.5 * (1 + sqr(F));
    F *= sqr(beta / (g + c));
    Kr = F;
    Kt = (1 - Kr) * eta * eta;
    T = refract(I, N, eta);
  } else {
    Kr = 1;
    Kt = 0;
    T = vector(0, 0, 0);
  }
}
void fresnel(vector I, normal N, float eta, output float Kr, output float Kt) {
  vector R, T;
  fresnel(I, N, eta, Kr, Kt, R, T);
}

// Rotation of a point by `angle` radians about the axis through a and b: the rotation matrix
// about the unit axis (x, y, z), entry by entry as OSL's stdosl.h writes it, applied to p - a, so
// that results agree with OSL's to the bit. A matrix carries no derivatives, so only those of p
// reach the result (as in OSL).
point rotate(point p, float angle, point a, point b) {
  vector axis = normalize(b - a);
  float cosang, sinang;
  sincos(angle, sinang, cosang);
  float cosang1 = 1.0 - cosang;
  float x = axis[0], y = axis[1], z = axis[2];
  matrix M = matrix(x * x + (1.0 - x * x) * cosang, x * y * cosang1 + z * sinang,
                    x * z * cosang1 - y * sinang, 0.0, x * y * cosang1 - z * sinang,
                    y * y + (1.0 - y * y) * cosang, y * z * cosang1 + x * sinang, 0.0,
                    x * z * cosang1 + y * sinang, y * z * cosang1 - x * sinang,
                    z * z + (1.0 - z * z) * cosang, 0.0, 0.0, 0.0, 0.0, 1.0);
  return transform(M, p - a) + a;
}
point rotate(point p, float angle, vector axis) { return rotate(p, angle, point(0), point(axis)); }

// Steps
float linearstep(float edge0, float edge1, float x) {
  float result;
  if (edge0 != edge1) {
    float xclamped = clamp(x, edge0, edge1);
    result = (xclamped - edge0) / (edge1 - edge0);
  } else {
    result = step(edge0, x);
  }
  return result;
}
color linearstep(color edge0, color edge1, color x) {
  return color(linearstep(edge0[0], edge1[0], x[0]), linearstep(edge0[1], edge1[1], x[1]),
               linearstep(edge0[2], edge1[2], x[2]));
}
float smooth_linearstep(float edge0, float edge1, float x_, float eps_) {
  float result;
  if (edge0 != edge1) {
    float rampup(float x, float r) { return 0.5 / r * x * x; }
    float width_inv = 1.0 / (edge1 - edge0);
    float eps = eps_ * width_inv;
    float x = (x_ - edge0) * width_inv;
    if (x <= -eps)
      result = 0;
    else if (x >= eps && x <= 1.0 - eps)
      result = x;
    else if (x >= 1.0 + eps)
      result = 1;
    else if (x < eps)
      result = rampup(x + eps, 2.0 * eps);
    else
      result = 1.0 - rampup(1.0 + eps - x, 2.0 * eps);
  } else {
    result = step(edge0, x_);
  }
  return result;
}
color smooth_linearstep(color edge0, color edge1, color x, color eps) {
  return color(smooth_linearstep(edge0[0], edge1[0], x[0], eps[0]),
               smooth_linearstep(edge0[1], edge1[1], x[1], eps[1]),
               smooth_linearstep(edge0[2], edge1[2], x[2], eps[2]));
}

// Antialiased step: a filtered step over the filter width of its argument.
float aastep(float edge, float s, float dedge, float ds) {
  float width = fabs(dedge) + fabs(ds);
  float halfwidth = 0.5 * width;
  float e1 = edge - halfwidth;
  return (s <= e1) ? 0.0 : ((s >= edge + halfwidth) ? 1.0 : (s - e1) / width);
}
float aastep(float edge, float s, float ds) { return aastep(edge, s, filterwidth(edge), ds); }
float aastep(float edge, float s) { return aastep(edge, s, filterwidth(edge), filterwidth(s)); }

// Conductor IOR from artistic parameters (Gulbrandsen, "Artist Friendly Metallic Fresnel",
// JCGT 3(4), 2014): the reflectivity at normal incidence r (clamped to [0, 0.99]) and the edge
// tint g give n = mix((1 + sqrt r) / (1 - sqrt r), (1 - r) / (1 + r), g) and
// k = sqrt(max(((n + 1)^2 r - (n - 1)^2) / (1 - r), 0)), per channel, for conductor_bsdf().
void artistic_ior(color reflectivity, color edge_tint, output color ior, output color extinction) {
  color r = clamp(reflectivity, 0.0, 0.99);
  color root = sqrt(r);
  ior = mix((1.0 + root) / (1.0 - root), (1.0 - r) / (1.0 + r), edge_tint);
  color above = ior + 1.0, below = ior - 1.0;
  extinction = sqrt(max((above * above * r - below * below) / (1.0 - r), 0.0));
}

// Renderer state: the ray-type tests OSL keeps for old shaders, and the matrix from a space
// to "common".
int iscameraray() { return raytype("camera"); }
int isdiffuseray() { return raytype("diffuse"); }
int isglossyray() { return raytype("glossy"); }
int isshadowray() { return raytype("shadow"); }
int getmatrix(string from, output matrix M) { return getmatrix(from, "common", M); }

// Displacement. bump() sets N to the normal the surface would have if it were moved by
// `offset` (common space), displace() also moves P. The new normal is that of the moved
// positions (calculatenormal from the derivatives of P + offset), corrected by how far the
// interpolated N was from the geometric Ng, so that smooth shading over facets stays smooth.
// With a float, the offset is along N, `amp` units measured in common space or in `space`.
void bump(vector offset) {
  normal smooth = normalize(N) - normalize(Ng);
  N = normalize(normalize(calculatenormal(P + offset)) + smooth);
}
void bump(float amp) { bump(amp * vector(normalize(N))); }
void bump(string space, float amp) {
  vector dir = vector(normalize(N));
  bump(amp / length(transform(space, dir)) * dir);
}
void displace(vector offset) {
  bump(offset);
  P += offset;
}
void displace(float amp) { displace(amp * vector(normalize(N))); }
void displace(string space, float amp) {
  vector dir = vector(normalize(N));
  displace(amp / length(transform(space, dir)) * dir);
}

#endif // STDOSL_H
