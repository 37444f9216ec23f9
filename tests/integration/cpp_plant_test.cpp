// The C++ SDK's plant helper (lagrange::sdk::ExternalPlant) in a run: filled in next.
