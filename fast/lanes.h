// fast/lanes.h -- numbers side by side, "lanes": what the fast wing computes several of at once,
// and the one place that says how, for the compiler and the processor at hand.
//
// With GCC or clang, a lane type is a vector extension (`vector_size`): one operator works on
// every lane, and the compiler turns it into vector instructions. Elsewhere, and when built with
// `make RT_SCALAR=1`, the same type is a plain struct of an array whose operators loop over the
// lanes, so that the very same kernels compile as scalar C++. Each lane of either form takes the
// same operations in the same order as the scalar code, so both give the same bits (the tests
// hold them to it: the fast search against the plain loop, every image against the others).
//
// What the compiler may lack, each with a plain fallback:
//   RT_VECTORS  vector extensions (GCC, clang), unless RT_SCALAR asks for the plain form;
//   RT_SHUFFLES __builtin_shufflevector (clang; GCC from version 12), for LaneBits and
//   OpenChildren; RT_DISPATCH a second copy of the kernel compiled for AVX2 on x86-64, chosen at
//   run time with
//               __builtin_cpu_supports (written out by hand: no ifunc, which macOS lacks).
#pragma once
#include <cstdint>
#include <cstring>
#include <type_traits>

#if !defined(RT_SCALAR) && (defined(__GNUC__) || defined(__clang__))
#define RT_VECTORS 1
#else
#define RT_VECTORS 0
#endif

#if RT_VECTORS && (defined(__clang__) || __GNUC__ >= 12)
#define RT_SHUFFLES 1
#else
#define RT_SHUFFLES 0
#endif

#if RT_VECTORS && defined(__x86_64__)
#define RT_DISPATCH 1
#define RT_AVX2 __attribute__((target("avx2")))
#else
#define RT_DISPATCH 0
#define RT_AVX2
#endif

// Always inlined, or never: the kernel's common case stays one function whose numbers stay in
// registers. (Attributes of GCC and clang; elsewhere plain inline and nothing, same answers.)
#if defined(__GNUC__) || defined(__clang__)
#define RT_INLINE inline __attribute__((always_inline))
#define RT_NOINLINE __attribute__((noinline))
#else
#define RT_INLINE inline
#define RT_NOINLINE
#endif

// The helpers below are always inlined (RT_INLINE), so that no call passes or returns a vector:
// a 256-bit vector passes differently with AVX than without, which GCC warns of (-Wpsabi).
#if defined(__GNUC__) || defined(__clang__)
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

#if RT_VECTORS

// RT_LANES(Name, T, N): Name holds N numbers of type T.
#define RT_LANES(Name, T, N) typedef T Name __attribute__((vector_size((N) * sizeof(T))))

// Lane by lane, a where the mask's lane is set (all ones), else b.
template <class Mask, class V> static RT_INLINE V Select(const Mask &mask, const V &a, const V &b) {
    return mask ? a : b;
}

#else // the plain form: a struct whose operators do, lane by lane, what a vector's would

// The integer a comparison of two T gives in each lane: as wide as T, -1 (all ones) for true.
template <class T> struct LaneIntOf;
template <> struct LaneIntOf<double> { typedef int64_t type; };
template <> struct LaneIntOf<float> { typedef int32_t type; };
template <> struct LaneIntOf<long long> { typedef long long type; };
template <> struct LaneIntOf<long> { typedef long type; };
template <> struct LaneIntOf<int> { typedef int type; };
template <> struct LaneIntOf<unsigned> { typedef int type; };
template <> struct LaneIntOf<char> { typedef char type; };

template <class T, int N> struct alignas(N * sizeof(T)) Pack {
    T lane[N];
    T &operator[](int i) { return lane[i]; }
    const T &operator[](int i) const { return lane[i]; }
};

#define RT_LANES(Name, T, N) typedef Pack<T, N> Name

// Each operator once for two packs; a number beside a pack stands in every lane, converted to the
// lanes' type.
template <class U> using ScalarOnly = typename std::enable_if<std::is_arithmetic<U>::value>::type;
#define RT_PACK_OPERATOR(op)                                                                       \
    template <class T, int N> static inline Pack<T, N> operator op(Pack<T, N> a, Pack<T, N> b) {   \
        for (int i = 0; i < N; i++)                                                                \
            a.lane[i] = a.lane[i] op b.lane[i];                                                    \
        return a;                                                                                  \
    }                                                                                              \
    template <class T, int N, class U, class = ScalarOnly<U>>                                      \
    static inline Pack<T, N> operator op(Pack<T, N> a, U b) {                                      \
        for (int i = 0; i < N; i++)                                                                \
            a.lane[i] = a.lane[i] op(T) b;                                                         \
        return a;                                                                                  \
    }                                                                                              \
    template <class T, int N, class U, class = ScalarOnly<U>>                                      \
    static inline Pack<T, N> operator op(U a, Pack<T, N> b) {                                      \
        for (int i = 0; i < N; i++)                                                                \
            b.lane[i] = (T)a op b.lane[i];                                                         \
        return b;                                                                                  \
    }                                                                                              \
    template <class T, int N, class U>                                                             \
    static inline Pack<T, N> &operator op##=(Pack<T, N> &a, const U &b) {                          \
        return a = a op b;                                                                         \
    }
RT_PACK_OPERATOR(+)
RT_PACK_OPERATOR(-)
RT_PACK_OPERATOR(*)
RT_PACK_OPERATOR(/)
RT_PACK_OPERATOR(&)
RT_PACK_OPERATOR(|)
RT_PACK_OPERATOR(^)
RT_PACK_OPERATOR(<<)
#undef RT_PACK_OPERATOR

template <class T, int N> static inline Pack<T, N> operator~(Pack<T, N> a) {
    for (int i = 0; i < N; i++)
        a.lane[i] = ~a.lane[i];
    return a;
}
template <class T, int N> static inline Pack<T, N> operator-(Pack<T, N> a) {
    for (int i = 0; i < N; i++)
        a.lane[i] = -a.lane[i];
    return a;
}

#define RT_PACK_COMPARISON(op)                                                                     \
    template <class T, int N>                                                                      \
    static inline Pack<typename LaneIntOf<T>::type, N> operator op(Pack<T, N> a, Pack<T, N> b) {   \
        Pack<typename LaneIntOf<T>::type, N> m;                                                    \
        for (int i = 0; i < N; i++)                                                                \
            m.lane[i] = a.lane[i] op b.lane[i] ? -1 : 0;                                           \
        return m;                                                                                  \
    }                                                                                              \
    template <class T, int N, class U, class = ScalarOnly<U>>                                      \
    static inline Pack<typename LaneIntOf<T>::type, N> operator op(Pack<T, N> a, U b) {            \
        Pack<typename LaneIntOf<T>::type, N> m;                                                    \
        for (int i = 0; i < N; i++)                                                                \
            m.lane[i] = a.lane[i] op(T) b ? -1 : 0;                                                \
        return m;                                                                                  \
    }
RT_PACK_COMPARISON(<)
RT_PACK_COMPARISON(<=)
RT_PACK_COMPARISON(>)
RT_PACK_COMPARISON(>=)
RT_PACK_COMPARISON(==)
RT_PACK_COMPARISON(!=)
#undef RT_PACK_COMPARISON

template <class M, int N, class T>
static inline Pack<T, N> Select(const Pack<M, N> &mask, const Pack<T, N> &a, const Pack<T, N> &b) {
    Pack<T, N> v;
    for (int i = 0; i < N; i++)
        v.lane[i] = mask.lane[i] ? a.lane[i] : b.lane[i];
    return v;
}

#endif

// Each lane converted to another lane type's numbers, as a scalar conversion would (C++'s rules:
// toward zero from floating point to integer).
template <class To, class From> static RT_INLINE To Convert(const From &from) {
#if RT_VECTORS
    return __builtin_convertvector(from, To);
#else
    To to;
    for (size_t i = 0; i < sizeof to / sizeof to[0]; i++)
        to[(int)i] = (typename std::remove_reference<decltype(to[0])>::type)from[(int)i];
    return to;
#endif
}

// The same bits read as another lane type of the same size (a vector cast, or memcpy).
template <class To, class From> static RT_INLINE To Bitcast(const From &from) {
    static_assert(sizeof(To) == sizeof(From), "a bit cast keeps the size");
    To to;
    memcpy(&to, &from, sizeof to);
    return to;
}

// The place of the lowest set bit of a nonzero word.
static inline int LowestBit(uint64_t bits) {
#if defined(__GNUC__) || defined(__clang__)
    return __builtin_ctzll(bits);
#else
    int k = 0;
    while (!(bits >> k & 1))
        k++;
    return k;
#endif
}
