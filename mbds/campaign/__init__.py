"""Campaigns: a job file expanded into chains of versions for parameter variants and
replicates (:mod:`mbds.campaign.plan`), their state in a ledger (:mod:`mbds.campaign.ledger`),
one task performed in-process for any executor (:mod:`mbds.campaign.tasks`) and Slurm batch
scripts (:mod:`mbds.campaign.slurm`). The user guide is docs/campaigns.md."""
