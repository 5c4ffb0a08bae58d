// The BSDF dispatch of evaluation, density and sampling for every member, out of line: bsdf.h
// takes Lambertian surfaces inline and calls these for the rest.
#include "materials/bsdf.h"

#include "core/frame.h"

namespace dualight::bsdf_dispatch {

Color eval_f(const Bsdf& b, const Vec3& wo, const Vec3& wi, TransportMode m) {
  return std::visit([&](const auto& x) { return dualight::eval_f(x, wo, wi, m); }, b);
}
float pdf_w(const Bsdf& b, const Vec3& wo, const Vec3& wi, TransportMode m) {
  return std::visit([&](const auto& x) { return dualight::pdf_w(x, wo, wi, m); }, b);
}
Color eval_f_world(const Bsdf& b, const Vec3& ns, const Vec3& wo, const Vec3& wi, TransportMode m) {
  const Frame frame = Frame::from_normal(ns);
  return bsdf_dispatch::eval_f(b, frame.to_local(wo), frame.to_local(wi), m);
}
float pdf_w_world(const Bsdf& b, const Vec3& ns, const Vec3& wo, const Vec3& wi, TransportMode m) {
  const Frame frame = Frame::from_normal(ns);
  return bsdf_dispatch::pdf_w(b, frame.to_local(wo), frame.to_local(wi), m);
}
bool sample(const Bsdf& b, const Vec3& wo, Point2 u, TransportMode m, BsdfSample& s) {
  return std::visit([&](const auto& x) { return dualight::sample(x, wo, u, m, s); }, b);
}

}  // namespace dualight::bsdf_dispatch
