#pragma once
// A test that holds a built-in scene to the claim its description makes, registered under the
// scene's name so that SceneClaims.EveryBuiltInSceneIsCovered finds, for every built-in scene,
// the tests that hold it to its claim: a new scene without one fails that test.
//
//     SCENE_CLAIM(SceneClaims, SpringFollowsItsExactSolution, "spring") { ... }
//     SCENE_CLAIM(SceneClaims, SwarmsSettle, "blow-dryer-swarm", "fountain-1m") { ... }
//
// The registration runs when the test program starts, whichever tests it then runs (ctest runs
// each test in a process of its own).
#include <initializer_list>
#include <map>
#include <string>

#include <gtest/gtest.h>

namespace pba::test {

/// Every registered claim: scene name -> "Suite.Test", as many as there are.
inline std::multimap<std::string, std::string>& sceneClaims()
{
    static std::multimap<std::string, std::string> claims;
    return claims;
}

inline bool claimScenes(std::initializer_list<const char*> scenes, const std::string& test)
{
    for (const char* scene : scenes)
        sceneClaims().emplace(scene, test);
    return true;
}

} // namespace pba::test

#define PBA_SCENE_CLAIM_NAME(suite, name) suite##_##name##_claim
#define SCENE_CLAIM(suite, name, ...)                                                                               \
    [[maybe_unused]] static const bool PBA_SCENE_CLAIM_NAME(suite, name) =                                        \
        ::pba::test::claimScenes({__VA_ARGS__}, #suite "." #name);                                                 \
    TEST(suite, name)
