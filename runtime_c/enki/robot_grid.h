/*
 * robot_grid.h - the robots' centres in square cells, made again after
 * each physics step (physics_chipmunk.cpp): what the IR sensors and the
 * message channel ask of the other robots, from every robot at every
 * step, from several threads at once.
 *
 * Chipmunk indexes the same bodies for its broad phase, but its
 * bounding-box tree costs about 2,000 instructions a query with 1,000
 * robots (callgrind; a tree of 1,000 leaves walked from its root) and its
 * spatial hash marks what each query visits, so that two threads cannot
 * query it at once.  A grid of equal discs is made in one pass (a counting
 * sort of the robots by cell) and read by any number of threads; a query
 * visits the few cells it overlaps, in order.  The static shapes stay in
 * Chipmunk's tree, which is small.
 */
#ifndef ROBOT_GRID_H
#define ROBOT_GRID_H

#include <algorithm>
#include <cmath>
#include <vector>

#include "world_channel.h"

namespace grid {

class Grid {
public:
    // the cells `cell` wide (wider when the robots are far apart: at most
    // about four cells a robot)
    void build(const std::vector<channel::Pose> &poses, double cell)
    {
        const size_t n = poses.size();
        double l = poses[0].x, r = l, b = poses[0].y, t = b;
        for (const channel::Pose &p : poses) {
            l = std::min(l, p.x);
            r = std::max(r, p.x);
            b = std::min(b, p.y);
            t = std::max(t, p.y);
        }
        const double most = 4.0 * n + 1024;
        while (((r - l) / cell + 1) * ((t - b) / cell + 1) > most)
            cell *= 2;
        x0_ = l;
        y0_ = b;
        cell_ = cell;
        nx_ = (long)((r - l) / cell) + 1;
        ny_ = (long)((t - b) / cell) + 1;
        start_.assign((size_t)(nx_ * ny_) + 1, 0);
        cell_of_.resize(n);
        for (size_t i = 0; i < n; i++) {
            long c = column(poses[i].x) + nx_ * row(poses[i].y);
            cell_of_[i] = c;
            start_[(size_t)c + 1]++;
        }
        for (size_t c = 1; c < start_.size(); c++)
            start_[c] += start_[c - 1];
        order_.resize(n);
        std::vector<long> next(start_.begin(), start_.end() - 1);
        for (size_t i = 0; i < n; i++)
            order_[(size_t)next[(size_t)cell_of_[i]]++] = i;
    }

    // f(i) for every robot whose centre lies in a cell that meets the box
    // [l, r] x [b, t]: cell by cell, row by row, each cell's robots in
    // ascending order
    template <class F>
    void each(double l, double b, double r, double t, F f) const
    {
        long c0 = std::max(0L, column(l)), c1 = std::min(nx_ - 1, column(r));
        long r0 = std::max(0L, row(b)), r1 = std::min(ny_ - 1, row(t));
        for (long y = r0; y <= r1; y++)
            for (long x = c0; x <= c1; x++) {
                size_t c = (size_t)(x + nx_ * y);
                for (long k = start_[c]; k < start_[c + 1]; k++)
                    f(order_[(size_t)k]);
            }
    }

private:
    double x0_ = 0, y0_ = 0, cell_ = 1;
    long nx_ = 1, ny_ = 1;
    std::vector<long> start_;       // each cell's first robot in order_
    std::vector<size_t> order_;     // the robots, cell by cell
    std::vector<long> cell_of_;

    long column(double x) const { return (long)std::floor((x - x0_) / cell_); }
    long row(double y) const { return (long)std::floor((y - y0_) / cell_); }
};

}  // namespace grid

#endif
