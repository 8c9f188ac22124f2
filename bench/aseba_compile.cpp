// A command-line front end to Aseba's own compiler, for bench/front_end_bench.py.
//
// The Debian package `aseba` ships no stand-alone compiler: its tools
// (asebamassloader, asebahttp, Aseba Studio) compile a program only to send
// it to a node on the network at once. The compiler itself is shipped as a
// static library with its headers (/usr/lib/libasebacompiler.a,
// /usr/include/aseba/compiler/compiler.h); this file calls it the way those
// tools do, on the target description of an e-puck running Aseba, so that
// `aseba_compile FILE.aesl-source` is the same job as `epuckc check FILE`:
// a whole process that reads, tokenises, parses and checks a program (and,
// unlike epuckc check, also generates and links its bytecode).
//
//   g++ -O2 -std=c++17 -I/usr/include/aseba bench/aseba_compile.cpp \
//       -lasebacompiler -lasebacommon -o aseba_compile
//   aseba_compile [--bytecode WORDS] program.aseba
//
// Exit status 0 when the program compiles (prints the bytecode size and
// the variables used), 1 with `file:line:column: error: message` when it
// does not, 2 when the file cannot be read.
#include <common/consts.h>
#include <compiler/compiler.h>

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>

using namespace Aseba;

// What an e-puck running Aseba (aseba/targets/e-puck) describes to the
// compiler: its variables and local events. The e-puck's VM has 1,024 words
// of bytecode; --bytecode raises it so that large programs can be timed.
static TargetDescription epuck_target(unsigned bytecode_words, unsigned variable_words)
{
    TargetDescription d;
    d.name = L"e-puck";
    d.protocolVersion = ASEBA_PROTOCOL_VERSION;
    d.bytecodeSize = bytecode_words;
    d.variablesSize = variable_words;
    d.stackSize = 32;
    const struct { const wchar_t *name; unsigned size; } vars[] = {
        {L"id", 1}, {L"source", 1}, {L"args", 32},
        {L"leftSpeed", 1}, {L"rightSpeed", 1},
        {L"prox", 8}, {L"ambiant", 8}, {L"acc", 3},
        {L"selector", 1}, {L"camLine", 60}, {L"timerPeriod", 1},
    };
    for (const auto &v : vars)
        d.namedVariables.emplace_back(v.name, v.size);
    d.localEvents.push_back({L"ir_sensors", L"new proximity readings (every 1/64 s)"});
    d.localEvents.push_back({L"timer", L"the timer's period has elapsed"});
    d.localEvents.push_back({L"acc", L"new accelerometer readings"});
    return d;
}

int main(int argc, char **argv)
{
    unsigned bytecode = 1024, variables = 1024;
    const char *path = nullptr;
    for (int i = 1; i < argc; i++) {
        if (std::strcmp(argv[i], "--bytecode") == 0 && i + 1 < argc)
            bytecode = static_cast<unsigned>(std::strtoul(argv[++i], nullptr, 10));
        else if (std::strcmp(argv[i], "--variables") == 0 && i + 1 < argc)
            variables = static_cast<unsigned>(std::strtoul(argv[++i], nullptr, 10));
        else
            path = argv[i];
    }
    if (path == nullptr) {
        std::cerr << "usage: aseba_compile [--bytecode WORDS] [--variables WORDS] FILE\n";
        return 2;
    }
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        std::cerr << "aseba_compile: cannot read " << path << "\n";
        return 2;
    }
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    // Aseba sources are wide strings; the benchmark's programs are ASCII.
    std::wistringstream source(std::wstring(bytes.begin(), bytes.end()));

    TargetDescription target = epuck_target(bytecode, variables);
    CommonDefinitions common;
    Compiler compiler;
    compiler.setTargetDescription(&target);
    compiler.setCommonDefinitions(&common);

    BytecodeVector code;
    unsigned allocated = 0;
    Error error;
    if (!compiler.compile(source, code, allocated, error)) {
        std::string message(error.message.begin(), error.message.end());
        std::cerr << path << ":" << error.pos.row + 1 << ":" << error.pos.column + 1
                  << ": error: " << message << "\n";
        return 1;
    }
    std::cout << "bytecode " << code.size() << " words, variables " << allocated << " words\n";
    return 0;
}
