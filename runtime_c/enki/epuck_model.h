/*
 * epuck_model.h - the e-puck's body and sensors as Enki models them, for
 * the providers that are not Enki (physics_chipmunk.cpp): the same
 * numbers and the same formulas, so that a world reads the same whichever
 * physics runs it.  Written from Enki's documented model (its headers in
 * /usr/include/enki and the e-puck's parameters in its EPuck.cpp, Enki
 * 1.6.99), not copied; units cm, radians, counter-clockwise; objects are
 * given in the world's frame.
 *
 * IR sensors (Enki's IRSensor with the e-puck's parameters).  Eight
 * sensors at fixed places on the body, 2.5 cm above the floor (an object
 * lower than that is not seen), each casting three rays 12 cm long, at -15,
 * 0 and +15 degrees from its direction.  A ray at distance x from the
 * nearest object it meets gives F(x) = m (c - x0^2) / (x^2 - 2 x0 x + c)
 * (m = 3731 below x0 = 0.3 cm, 0 beyond the range), the central ray
 * F(x) - 2 F(x / cos 15 deg); the sensor's value is their sum plus
 * Gaussian noise of standard deviation 10, clamped to 0..m.  An object is
 * tried by a sensor when its bounding circle is within the sensor's reach
 * of the body's centre and meets the circle around its rays; a cylinder's
 * ray distance is to its circle along the ray's line (as Enki's, also for
 * a circle the line meets behind the sensor), a box's to its polygon.
 * The walls are tried when the rays' circle reaches over them; a sensor
 * over a wall reads 0 (plus noise).
 *
 * Camera (Enki's CircularCam as the e-puck has it): at the front of the
 * body, 2.2 cm high, 60 pixels over 60 degrees, pixel 0 at the right edge.
 * A cylinder covers the pixels from floor to ceil of its angular extent
 * (its centre's bearing +- atan(radius / distance)) at the depth of its
 * centre; a polygon's edges and the walls are drawn pixel by pixel where
 * each pixel's ray meets them.  The nearest wins; a pixel that meets
 * nothing has the world's colour.
 */
#ifndef EPUCK_MODEL_H
#define EPUCK_MODEL_H

#include <algorithm>
#include <cmath>
#include <limits>

namespace epuck {

const double PI = 3.14159265358979323846;
const double RADIUS = 3.7, HEIGHT = 4.7, MASS = 152;

// ---- the IR sensors -------------------------------------------------------

struct IrPlace {
    double x, y, orientation;       // on the body, its heading along +x
};
const IrPlace IR_PLACES[8] = {
    {3.35, -1.05, -18 * PI / 180}, {2.3, -2.6, -45 * PI / 180}, {0.0, -3.3, -90 * PI / 180},
    {-3.0, -1.8, -142 * PI / 180}, {-3.0, 1.8, 142 * PI / 180}, {0.0, 3.3, 90 * PI / 180},
    {2.3, 2.6, 45 * PI / 180}, {3.35, 1.05, 18 * PI / 180},
};
const double IR_HEIGHT = 2.5, IR_RANGE = 12, IR_M = 3731, IR_X0 = 0.3, IR_C = 0.7;
const double IR_NOISE_SD = 10, IR_APERTURE = 15 * PI / 180;

inline double ir_response(double x)
{
    if (x < IR_X0)
        return IR_M;
    if (x > IR_RANGE)
        return 0;
    return IR_M * (IR_C - IR_X0 * IR_X0) / (x * x - 2 * IR_X0 * x + IR_C);
}

// The radius around the body's centre within which sensor k reaches.
inline double ir_reach(int k)
{
    const IrPlace &s = IR_PLACES[k];
    double n2 = s.x * s.x + s.y * s.y, n = std::sqrt(n2);
    return std::sqrt(n2 + IR_RANGE * IR_RANGE
                     - 2 * n * IR_RANGE * std::cos(PI - s.orientation + std::atan2(s.y, s.x)));
}

// The circle around a sensor's three rays: its radius, and its centre's
// distance ahead of the sensor.
inline double ir_rays_radius() { return IR_RANGE * std::sqrt(1.25 - std::cos(IR_APERTURE)); }
const double IR_RAYS_AHEAD = IR_RANGE / 2;

// How far from the body's centre anything an IR sensor may see can be:
// the boxes of what the physics is asked about.
inline double ir_extent()
{
    double most = 0;
    for (int k = 0; k < 8; k++) {
        const IrPlace &s = IR_PLACES[k];
        double cx = s.x + IR_RAYS_AHEAD * std::cos(s.orientation);
        double cy = s.y + IR_RAYS_AHEAD * std::sin(s.orientation);
        most = std::max(most, std::hypot(cx, cy) + ir_rays_radius());
    }
    return most;
}

// The sensors' rays in the body's frame: each ray's direction, and the
// centre of each sensor's rays' circle (computed once).
struct IrFrame {
    double ray[8][3][2];
    double centre[8][2];
    IrFrame()
    {
        for (int k = 0; k < 8; k++) {
            const IrPlace &s = IR_PLACES[k];
            for (int i = 0; i < 3; i++) {
                ray[k][i][0] = std::cos(s.orientation + (i - 1) * IR_APERTURE);
                ray[k][i][1] = std::sin(s.orientation + (i - 1) * IR_APERTURE);
            }
            centre[k][0] = s.x + IR_RAYS_AHEAD * std::cos(s.orientation);
            centre[k][1] = s.y + IR_RAYS_AHEAD * std::sin(s.orientation);
        }
    }
};

// One sensor of a body at (bx, by) heading (cos c, sin s), its rays being
// traced.  The angle between a ray and the direction v of an object's
// centre enters Enki's formulas only through |v| sin and |v| cos of it,
// taken here from cross and dot products with the ray's direction.
struct IrSensor {
    double x, y;                    // in the world
    double dir[3][2];               // each ray's direction, in the world
    double sx, sy;                  // the centre of its rays' circle
    double dist[3], value[3];

    void start(const IrFrame &f, int k, double bx, double by, double c, double s)
    {
        const IrPlace &p = IR_PLACES[k];
        x = bx + c * p.x - s * p.y;
        y = by + s * p.x + c * p.y;
        for (int i = 0; i < 3; i++) {
            const double *d = f.ray[k][i];
            dir[i][0] = c * d[0] - s * d[1];
            dir[i][1] = s * d[0] + c * d[1];
            dist[i] = IR_RANGE;
            value[i] = 0;
        }
        sx = bx + c * f.centre[k][0] - s * f.centre[k][1];
        sy = by + s * f.centre[k][0] + c * f.centre[k][1];
    }

    // a ray meets something at `d`
    void update(int i, double d)
    {
        if (d < dist[i]) {
            dist[i] = d;
            value[i] = ir_response(d);
            if (i == 1)
                value[i] -= 2 * ir_response(d / std::cos(IR_APERTURE));
        }
    }

    // Whether an object of bounding circle (ox, oy, radius), `height` high,
    // is tried: its circle meets the rays' circle, and it is not lower.
    bool tries(double ox, double oy, double radius, double height) const
    {
        if (IR_HEIGHT > height)
            return false;
        double dx = ox - sx, dy = oy - sy, sum = radius + ir_rays_radius();
        return dx * dx + dy * dy <= sum * sum;
    }

    void cylinder(double ox, double oy, double radius)
    {
        double vx = ox - x, vy = oy - y, v2 = vx * vx + vy * vy, r2 = radius * radius;
        for (int i = 0; i < 3; i++) {
            double cross = dir[i][0] * vy - dir[i][1] * vx;
            double across2 = cross * cross;
            if (across2 <= r2)
                update(i, std::max(std::sqrt(std::max(v2 - across2, 0.0))
                                   - std::sqrt(r2 - across2), 0.0));
        }
    }

    // a convex polygon (counter-clockwise), its bounding circle (ox, oy, radius)
    void polygon(const double (*p)[2], int n, double ox, double oy, double radius)
    {
        double vx = ox - x, vy = oy - y;
        for (int i = 0; i < 3; i++) {
            double cross = dir[i][0] * vy - dir[i][1] * vx;
            if (cross * cross < radius * radius)
                update(i, to_polygon(dir[i], p, n));
        }
    }

    // the walls of a w x h arena; a sensor over a wall reads nothing
    void walls(double w, double h)
    {
        const double rr = ir_rays_radius();
        if (sx - rr > 0 && sy - rr > 0 && sx + rr < w && sy + rr < h)
            return;
        if (x < 0 || x > w || y < 0 || y > h) {
            for (int i = 0; i < 3; i++) {
                dist[i] = IR_M;
                value[i] = 0;
            }
            return;
        }
        for (int i = 0; i < 3; i++) {
            double ex = x + dir[i][0] * IR_RANGE, ey = y + dir[i][1] * IR_RANGE;
            const double none = std::numeric_limits<double>::infinity();
            double across = none, along = none;
            if (ex < 0)
                across = -x / (ex - x);
            else if (ex > w)
                across = (w - x) / (ex - x);
            if (ey < 0)
                along = -y / (ey - y);
            else if (ey > h)
                along = (h - y) / (ey - y);
            update(i, std::min(across, along) * IR_RANGE);
        }
    }

    double sum() const { return value[0] + value[1] + value[2]; }

private:
    // The distance along the ray to where it enters the polygon (0 from
    // inside), infinity when it misses it within the range: a line
    // clipped by each edge's half-plane in turn.
    double to_polygon(const double *d, const double (*p)[2], int n) const
    {
        const double none = std::numeric_limits<double>::infinity();
        double dx = d[0] * IR_RANGE, dy = d[1] * IR_RANGE;
        double enter = 0, leave = 1;
        for (int k = 0; k < n; k++) {
            const double *a = p[k], *b = p[k + 1 == n ? 0 : k + 1];
            double ex = b[0] - a[0], ey = b[1] - a[1];
            double num = ex * (y - a[1]) - ey * (x - a[0]);
            double den = -(ex * dy - ey * dx);
            if (std::fabs(den) < 1e-8) {
                if (num < 0)
                    return none;
                continue;
            }
            double t = num / den;
            if (den < 0) {
                if (t > enter && (enter = t) > leave)
                    return none;
            } else if (t < leave && (leave = t) < enter) {
                return none;
            }
        }
        return std::hypot(dx * enter, dy * enter);
    }
};

// ---- the camera -----------------------------------------------------------

const int CAMERA_PIXELS = 60;
const double CAMERA_X = 3.7, CAMERA_HEIGHT = 2.2, CAMERA_HALF_FOV = PI / 6;

inline double wrap(double a)
{
    while (a > PI)
        a -= 2 * PI;
    while (a < -PI)
        a += 2 * PI;
    return a;
}

struct Camera {
    double x, y, heading;                   // in the world
    double z[CAMERA_PIXELS];                // each pixel's depth, squared
    double image[CAMERA_PIXELS][3];

    void start(double bx, double by, double body_heading, const double *background)
    {
        x = bx + std::cos(body_heading) * CAMERA_X;
        y = by + std::sin(body_heading) * CAMERA_X;
        heading = body_heading;
        for (int i = 0; i < CAMERA_PIXELS; i++) {
            z[i] = std::numeric_limits<double>::max();
            std::copy(background, background + 3, image[i]);
        }
    }

    // whether every pixel has met something nearer than `d`
    bool within(double d) const
    {
        for (int i = 0; i < CAMERA_PIXELS; i++)
            if (z[i] > d * d)
                return false;
        return true;
    }

    void cylinder(double ox, double oy, double radius, const double *rgb)
    {
        double cx = ox - x, cy = oy - y, d = std::hypot(cx, cy);
        if (radius == 0 || d == 0)
            return;
        double bearing = wrap(std::atan2(cy, cx) - heading);
        double half = std::atan(radius / d);
        double begin = bearing - half, end = bearing + half;
        if (begin > CAMERA_HALF_FOV || end < -CAMERA_HALF_FOV)
            return;
        begin = std::max(begin, -CAMERA_HALF_FOV);
        end = std::min(end, CAMERA_HALF_FOV);
        size_t first = (size_t)std::floor((CAMERA_PIXELS - 1) * 0.5 * (begin / CAMERA_HALF_FOV + 1));
        size_t last = (size_t)std::ceil((CAMERA_PIXELS - 1) * 0.5 * (end / CAMERA_HALF_FOV + 1));
        for (size_t i = first; i <= last && i < (size_t)CAMERA_PIXELS; i++)
            paint(i, d * d, rgb);
    }

    // one straight edge, from (ax, ay) to (bx, by)
    void line(double ax, double ay, double bx, double by, const double *rgb)
    {
        // into the camera's frame, the optical axis along +x
        double c = std::cos(-heading), s = std::sin(-heading);
        double p0x = c * (ax - x) - s * (ay - y), p0y = s * (ax - x) + c * (ay - y);
        double p1x = c * (bx - x) - s * (by - y), p1y = s * (bx - x) + c * (by - y);
        double d0 = std::atan2(p0y, p0x), d1 = std::atan2(p1y, p1x);
        if (d0 > d1) {
            std::swap(d0, d1);
            std::swap(p0x, p1x);
            std::swap(p0y, p1y);
        }
        const double fov = CAMERA_HALF_FOV;
        if (d1 - d0 > PI) {             // the edge passes behind the camera
            if (d0 < -fov && d1 > fov)
                return;
            std::swap(d0, d1);
            std::swap(p0x, p1x);
            std::swap(p0y, p1y);
            if (d1 < -fov)
                d1 += 2 * PI;
            else
                d0 -= 2 * PI;
        }
        if (!(d1 > d0) || d1 < -fov || d0 > fov)
            return;
        const double step = 2 * fov / (CAMERA_PIXELS - 1);
        double begin = -fov + std::ceil((std::max(d0, -fov) + fov) / step) * step;
        double end = -fov + std::floor((std::min(d1, fov) + fov) / step) * step;
        size_t first = (size_t)std::round((begin + fov) / (2 * fov) * (CAMERA_PIXELS - 1));
        size_t last = (size_t)std::round((end + fov) / (2 * fov) * (CAMERA_PIXELS - 1));
        double ex = p1x - p0x, ey0 = p0y - p1y;
        double angle = begin;
        for (size_t i = first; i <= last && i < (size_t)CAMERA_PIXELS; i++, angle += step) {
            double lambda;
            if (std::fabs(angle) == PI / 2) {
                lambda = -p0x / ex;
            } else {
                double t = std::tan(angle);
                lambda = (p0y - p0x * t) / (t * ex + ey0);
            }
            double px, py;
            if (lambda < 0) {
                px = p0x;
                py = p0y;
            } else if (lambda >= 1) {
                px = p1x;
                py = p1y;
            } else {
                px = p0x + ex * lambda;
                py = p0y + (p1y - p0y) * lambda;
            }
            paint(i, px * px + py * py, rgb);
        }
    }

    void walls(double w, double h, const double *rgb)
    {
        line(0, 0, w, 0, rgb);
        line(w, 0, w, h, rgb);
        line(w, h, 0, h, rgb);
        line(0, h, 0, 0, rgb);
    }

private:
    void paint(size_t i, double depth2, const double *rgb)
    {
        if (depth2 < z[i]) {
            z[i] = depth2;
            std::copy(rgb, rgb + 3, image[i]);
        }
    }
};

}  // namespace epuck

#endif
