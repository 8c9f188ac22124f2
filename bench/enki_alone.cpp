/*
 * enki_alone.cpp - Enki alone, the reference of bench/world_bench.py: the
 * same world as the bench's (a walled arena, a cylinder, a box, N
 * e-pucks in rows) stepped for the same simulated time at the same 10 ms
 * step, each e-puck with its eight IR sensors (no scanner turret, as the
 * world runner) and a trivial controller (a Braitenberg avoider on the IR
 * values), nothing else: no program, no runtime, no trace.
 *
 *   c++ -O2 bench/enki_alone.cpp -o enki_alone -lenki && ./enki_alone 50 60
 */
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include <enki/PhysicalEngine.h>
#include <enki/robots/e-puck/EPuck.h>

struct Bot : public Enki::EPuck {
    Bot() : Enki::EPuck(CAPABILITY_NONE)
    {
        addLocalInteraction(&infraredSensor0);
        addLocalInteraction(&infraredSensor1);
        addLocalInteraction(&infraredSensor2);
        addLocalInteraction(&infraredSensor3);
        addLocalInteraction(&infraredSensor4);
        addLocalInteraction(&infraredSensor5);
        addLocalInteraction(&infraredSensor6);
        addLocalInteraction(&infraredSensor7);
    }
};

int main(int argc, char **argv)
{
    int robots = argc > 1 ? std::atoi(argv[1]) : 50;
    int seconds = argc > 2 ? std::atoi(argv[2]) : 60;
    int cols = 10, rows = (robots + cols - 1) / cols;
    double width = cols * 30 + 40, height = rows * 30 + 100;
    Enki::World world(width, height);
    world.setRandomSeed(1);
    Enki::PhysicalObject *cyl = new Enki::PhysicalObject;
    cyl->setCylindric(8, 5, -1);
    cyl->pos = Enki::Point(width / 2, height - 25);
    world.addObject(cyl);
    Enki::PhysicalObject *box = new Enki::PhysicalObject;
    box->setRectangular(30, 6, 5, -1);
    box->pos = Enki::Point(width / 4, height - 30);
    box->angle = 20 * M_PI / 180;
    world.addObject(box);
    std::vector<Bot *> bots;
    for (int i = 0; i < robots; i++) {
        Bot *b = new Bot;
        b->pos = Enki::Point(35 + (i % cols) * 30, 35 + (i / cols) * 30);
        b->angle = ((i * 37) % 360) * M_PI / 180;
        world.addObject(b);
        bots.push_back(b);
    }
    long steps = (long)seconds * 100;
    for (long s = 0; s < steps; s++) {
        for (Bot *b : bots) {
            double right = b->infraredSensor0.getValue() + b->infraredSensor1.getValue();
            double left = b->infraredSensor7.getValue() + b->infraredSensor6.getValue();
            b->leftSpeed = 6.4 - right / 400;
            b->rightSpeed = 6.4 - left / 400;
        }
        world.step(0.01);
    }
    double sum = 0;
    for (Bot *b : bots)
        sum += b->pos.x + b->pos.y;
    std::printf("%d robots, %d s, checksum %.3f\n", robots, seconds, sum);
    return 0;
}
